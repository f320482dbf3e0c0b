// SPDX-License-Identifier: BSD-3-Clause
// Shared helpers for the C++ tests of the VTK classes (<Stage>/Testing/Cxx/Test*.cxx): an
// error/warning observer, field-data lookup; the check macros are AnisoTestChecks.h's.
#ifndef vtkAnisoTestUtilities_h
#define vtkAnisoTestUtilities_h

#include "AnisoTestChecks.h" // AV_CHECK, AV_TEST_RESULT

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace av_vtk_test
{
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

} // namespace av_vtk_test

#endif
