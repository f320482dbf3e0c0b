// SPDX-License-Identifier: BSD-3-Clause
// The anisovoronoi tool's VTK output window.
#include "CapturingOutputWindow.h"

#include <iostream>

namespace avcli
{

std::string VtkMessageText(const char* text)
{
  std::string t = text;
  const std::size_t colon = t.find("): ");
  t = colon == std::string::npos ? t : t.substr(colon + 3);
  while (!t.empty() && (t.back() == '\n' || t.back() == ' '))
    t.pop_back();
  return t;
}

CapturingOutputWindow* CapturingOutputWindow::New()
{
  return new CapturingOutputWindow;
}

void CapturingOutputWindow::DisplayErrorText(const char* text)
{
  if (this->FirstError.empty() && text)
    this->FirstError = VtkMessageText(text);
}

void CapturingOutputWindow::DisplayWarningText(const char* text)
{
  if (this->ShowWarnings && text)
    std::cerr << "[anisovoronoi] warning: " << text << std::flush;
}

} // namespace avcli
