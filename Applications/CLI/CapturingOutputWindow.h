// SPDX-License-Identifier: BSD-3-Clause
// CapturingOutputWindow: the anisovoronoi tool's VTK output window (first error kept for the
// one-line failure message, warnings to stderr), and the VTK message text without its prefix.
#ifndef avcli_CapturingOutputWindow_h
#define avcli_CapturingOutputWindow_h

#include <vtkOutputWindow.h>

#include <string>

namespace avcli
{

/// The message of a VTK error / warning text: VTK prefixes "ERROR: In file, line N\nclass
/// (0x...): message"; this keeps "message", without trailing newlines and blanks.
std::string VtkMessageText(const char* text);

/**
 * Receives every VTK error/warning: errors raised inside helper objects (e.g. the legacy
 * reader's internal reader) reach no algorithm observer, so they are collected here.
 */
class CapturingOutputWindow : public vtkOutputWindow
{
public:
  static CapturingOutputWindow* New();
  void DisplayErrorText(const char* text) override;
  void DisplayWarningText(const char* text) override;
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::string FirstError;
  bool ShowWarnings = true;
};

} // namespace avcli

#endif
