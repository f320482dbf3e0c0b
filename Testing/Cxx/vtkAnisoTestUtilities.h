// Shared helpers for the C++ tests of the VTK classes (Testing/Cxx/Test*.cxx): check macros
// that count failures instead of aborting, an error/warning observer, field-data lookup.
// Header only and not named Test*.cxx, so the test glob does not turn it into a test; the
// tests include it with quotes, which finds it next to them.
#ifndef vtkAnisoTestUtilities_h
#define vtkAnisoTestUtilities_h

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace av_vtk_test
{
/// Number of failed checks so far in this executable.
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

/// Exit code of the test: prints the failure count (or "<name> passed") and returns 0 / 1.
inline int Result(const char* name)
{
  if (Failures())
  {
    std::printf("%d check(s) failed\n", Failures());
    return 1;
  }
  std::printf("%s passed\n", name);
  return 0;
}

/**
 * Counts the error and warning events it observes (keeps the test output clean) and keeps the
 * last message and all messages concatenated. Attach it with Watch() or AddObserver().
 */
class EventCounter : public vtkCommand
{
public:
  static EventCounter* New() { return new EventCounter; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
    this->Last = data ? static_cast<const char*>(data) : "";
    this->All += this->Last;
  }
  void Reset()
  {
    this->Errors = this->Warnings = 0;
    this->Last.clear();
    this->All.clear();
  }
  int Errors = 0;
  int Warnings = 0;
  std::string Last;
  std::string All;
};

/// Observes errors and warnings of `alg` and errors of its executive (failed requests).
inline void Watch(vtkAlgorithm* alg, EventCounter* counter)
{
  alg->AddObserver(vtkCommand::ErrorEvent, counter);
  alg->AddObserver(vtkCommand::WarningEvent, counter);
  alg->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, counter);
}

/// First value of the field-data array `name`, NaN when it is missing.
inline double FieldValue(vtkDataObject* o, const char* name)
{
  vtkDataArray* a = o->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::nan("");
}

/// Seconds elapsed since t0.
inline double Seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace av_vtk_test

/// Counts a failure (and prints the line) when `cond` is false; the test goes on.
#define CHECK(cond)                                                                                \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::printf("FAILED line %d: %s\n", __LINE__, #cond);                                        \
      ++av_vtk_test::Failures();                                                                   \
    }                                                                                              \
  } while (0)

/// Counts a failure when |a - b| > tol (or either is NaN).
#define CHECK_NEAR(a, b, tol)                                                                      \
  do                                                                                               \
  {                                                                                                \
    const double va_ = (a), vb_ = (b);                                                             \
    if (!(std::abs(va_ - vb_) <= (tol)))                                                           \
    {                                                                                              \
      std::printf("FAILED line %d: %s = %.17g, expected %.17g\n", __LINE__, #a, va_, vb_);         \
      ++av_vtk_test::Failures();                                                                   \
    }                                                                                              \
  } while (0)

#endif
