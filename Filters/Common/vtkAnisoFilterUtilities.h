// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkAnisoFilterUtilities.h
 * @brief Internal (not wrapped): what every AnisoVoronoi filter's RequestData does the same
 * way: run a kernel and turn its exceptions into a filter error, and add one-value field data.
 */
#ifndef vtkAnisoFilterUtilities_h
#define vtkAnisoFilterUtilities_h

#include "AnisoVoronoiFiltersCommonModule.h" // export macro
#include "InputError.h"                      // av::InputError, caught by RunKernel

#include <vtkAlgorithm.h> // vtkErrorWithObjectMacro on a filter

#include <exception>
#include <new>
#include <type_traits>

class vtkFieldData;

namespace vtkAnisoFilterUtilities
{
/// Adds (or replaces) a one-tuple double array `name` holding `value` in `fd`.
ANISOVORONOIFILTERSCOMMON_EXPORT void AddFieldValue(vtkFieldData* fd,
  const char* name,
  double value);

/**
 * Runs `kernel()` for `filter`. Bad input (av::InputError) becomes an error with the kernel's
 * message, exhausted memory "out of memory: <what>", any other exception an error
 * "<what> failed: <message>". Returns false on error, so that RequestData can `return 0`.
 */
template <class Kernel>
bool RunKernel(vtkAlgorithm* filter, const char* what, Kernel&& kernel)
{
  // A kernel fails by throwing: a value returned from it would be silently dropped.
  static_assert(std::is_void<decltype(kernel())>::value,
    "RunKernel: the kernel must return void (throw av::InputError to fail)");
  try
  {
    kernel();
    return true;
  }
  catch (const av::InputError& e)
  {
    vtkErrorWithObjectMacro(filter, << e.what());
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorWithObjectMacro(filter, << "out of memory: " << what);
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(filter, << what << " failed: " << e.what());
  }
  return false;
}
}

#endif
