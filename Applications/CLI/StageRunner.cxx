// SPDX-License-Identifier: BSD-3-Clause
// The anisovoronoi tool's stage runner.
#include "StageRunner.h"

#include "CapturingOutputWindow.h"
#include "CommandLine.h"
#include "Stopwatch.h"

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>

#include <iostream>

namespace avcli
{
namespace
{
/// Collects the first error a VTK algorithm reports, so it can be printed as one line.
class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    if (this->Message.empty() && data)
      this->Message = VtkMessageText(static_cast<const char*>(data));
  }
  std::string Message;
};
} // namespace

void StageRunner::Run(vtkAlgorithm* algorithm, const std::string& stage)
{
  vtkNew<ErrorCatcher> catcher;
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, catcher);
  const unsigned long execTag =
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  if (!this->Quiet)
    std::cerr << "[anisovoronoi] " << stage << " ..." << std::flush;
  const av::Stopwatch watch;
  auto* window = static_cast<CapturingOutputWindow*>(vtkOutputWindow::GetInstance());
  window->FirstError.clear();
  algorithm->Update();
  if (catcher->Message.empty() && !window->FirstError.empty())
    catcher->Message = window->FirstError;
  const double seconds = watch.Seconds();
  algorithm->RemoveObserver(tag);
  algorithm->GetExecutive()->RemoveObserver(execTag);
  if (!catcher->Message.empty())
  {
    if (!this->Quiet)
      std::cerr << " failed" << std::endl;
    Fail(stage + ": " + catcher->Message);
  }
  if (!this->Quiet)
    std::cerr << " " << seconds << " s" << std::endl;
  this->Seconds[stage] = seconds;
}

double StageRunner::SecondsOf(const std::string& stage) const
{
  const auto it = this->Seconds.find(stage);
  return it == this->Seconds.end() ? 0.0 : it->second;
}

} // namespace avcli
