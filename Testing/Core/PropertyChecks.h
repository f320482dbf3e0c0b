// SPDX-License-Identifier: BSD-3-Clause
// PropertyChecks: a list of properties a run must keep, collected instead of failing at once, so
// that a mutation test can show the same checks catch a broken run (the mesh improvement tests).
#ifndef av_PropertyChecks_h
#define av_PropertyChecks_h

#include <iostream>

namespace av_test
{

struct Checks
{
  bool Ok = true;
  void Expect(bool cond, const char* what)
  {
    if (!cond)
    {
      Ok = false;
      std::cerr << "  property broken: " << what << std::endl;
    }
  }
};

} // namespace av_test

#endif
