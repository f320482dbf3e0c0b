// SPDX-License-Identifier: BSD-3-Clause
// InputError: how every kernel reports bad input.
#ifndef av_InputError_h
#define av_InputError_h

#include <stdexcept>
#include <string>

namespace av
{

/// Every kernel reports bad input by throwing this; VTK filters turn it into vtkErrorMacro.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& what)
    : std::runtime_error(what)
  {
  }
};

} // namespace av

#endif
