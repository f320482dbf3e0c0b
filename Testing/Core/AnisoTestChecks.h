// SPDX-License-Identifier: BSD-3-Clause
// The check macros of every C++ test (kernels and VTK classes): a failed check prints where
// and why, the test goes on, and AV_TEST_RESULT() makes it return non-zero.
#ifndef av_AnisoTestChecks_h
#define av_AnisoTestChecks_h

#include <cmath>
#include <cstdlib>
#include <iostream>

#include "InputError.h" // AV_CHECK_THROWS

namespace av_test
{
inline int& Failures()
{
  static int failures = 0;
  return failures;
}
}

#define AV_CHECK(cond)                                                                       \
  do                                                                                         \
  {                                                                                          \
    if (!(cond))                                                                             \
    {                                                                                        \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;      \
      ++av_test::Failures();                                                                 \
    }                                                                                        \
  } while (0)

#define AV_CHECK_MSG(cond, msg)                                                              \
  do                                                                                         \
  {                                                                                          \
    if (!(cond))                                                                             \
    {                                                                                        \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << " -- " << msg  \
                << std::endl;                                                                \
      ++av_test::Failures();                                                                 \
    }                                                                                        \
  } while (0)

#define AV_CHECK_NEAR(a, b, tol)                                                             \
  do                                                                                         \
  {                                                                                          \
    const double av_a_ = (a), av_b_ = (b);                                                   \
    if (!(std::abs(av_a_ - av_b_) <= (tol)))                                                 \
    {                                                                                        \
      std::cerr << __FILE__ << ":" << __LINE__ << ": " #a " = " << av_a_ << " vs " #b " = "   \
                << av_b_ << " (tol " << (tol) << ")" << std::endl;                           \
      ++av_test::Failures();                                                                 \
    }                                                                                        \
  } while (0)

/// Expects `stmt` to throw av::InputError.
#define AV_CHECK_THROWS(stmt)                                                                \
  do                                                                                         \
  {                                                                                          \
    bool av_thrown_ = false;                                                                 \
    try                                                                                      \
    {                                                                                        \
      stmt;                                                                                  \
    }                                                                                        \
    catch (const av::InputError&)                                                            \
    {                                                                                        \
      av_thrown_ = true;                                                                     \
    }                                                                                        \
    if (!av_thrown_)                                                                         \
    {                                                                                        \
      std::cerr << __FILE__ << ":" << __LINE__ << ": expected InputError from " #stmt         \
                << std::endl;                                                                \
      ++av_test::Failures();                                                                 \
    }                                                                                        \
  } while (0)

#define AV_TEST_RESULT()                                                                     \
  (av_test::Failures() == 0 ? EXIT_SUCCESS                                                   \
                            : (std::cerr << av_test::Failures() << " check(s) failed\n", EXIT_FAILURE))

#endif
