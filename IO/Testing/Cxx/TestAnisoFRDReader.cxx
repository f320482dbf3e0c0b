// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoFRDReader on a hand-made one-element he20 file (node order, step selection,
// tensor/vector arrays, errors) and, when installed (Debian calculix-cgx-examples), on the
// real CalculiX compressor example, read at run time and never copied into the repository.
#include "vtkAnisoTestUtilities.h" // CHECK, EventCounter, Result
#include "vtkAnisoFRDReader.h"

#include <vtkCell.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

namespace
{

/// Number of quadratic-hexahedron edges whose mid node is farther than relTol * edge
/// length from the midpoint of its end nodes (VTK's own edge definition).
int WrongMidEdges(vtkUnstructuredGrid* ug, double relTol)
{
  int wrong = 0;
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < ug->GetNumberOfCells(); ++c)
  {
    ug->GetCell(c, cell);
    if (cell->GetCellType() != VTK_QUADRATIC_HEXAHEDRON)
    {
      continue;
    }
    for (int e = 0; e < cell->GetNumberOfEdges(); ++e)
    {
      vtkCell* edge = cell->GetEdge(e);
      double a[3], b[3], m[3];
      edge->GetPoints()->GetPoint(0, a);
      edge->GetPoints()->GetPoint(1, b);
      edge->GetPoints()->GetPoint(2, m);
      double len = 0, err = 0;
      for (int k = 0; k < 3; ++k)
      {
        len += (a[k] - b[k]) * (a[k] - b[k]);
        err = std::max(err, std::abs(m[k] - 0.5 * (a[k] + b[k])));
      }
      wrong += err > relTol * std::sqrt(len) ? 1 : 0;
    }
  }
  return wrong;
}

std::string Line(const char* fmt, ...)
{
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof(buf), fmt, ap);
  va_end(ap);
  return std::string(buf) + "\n";
}

/// One unit-cube he20 in frd node order (bottom, vertical, top mid-edges), 2 steps.
std::string OneHex()
{
  const double c[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
                           { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  const int frdEdges[12][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 5 },
                                { 2, 6 }, { 3, 7 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 } };
  double p[20][3];
  for (int i = 0; i < 8; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      p[i][k] = c[i][k];
    }
  }
  for (int e = 0; e < 12; ++e)
  {
    for (int k = 0; k < 3; ++k)
    {
      p[8 + e][k] = 0.5 * (c[frdEdges[e][0]][k] + c[frdEdges[e][1]][k]);
    }
  }
  std::string s = "    1C\n";
  s += Line("    2C%18s%12d%37s%1d", "", 20, "", 1);
  for (int i = 0; i < 20; ++i)
  {
    s += Line(" -1%10d%12.5E%12.5E%12.5E", i + 1, p[i][0], p[i][1], p[i][2]);
  }
  s += " -3\n";
  s += Line("    3C%18s%12d%37s%1d", "", 1, "", 1);
  s += Line(" -1%10d%5d%5d%5d", 1, 4, 0, 1);
  s += " -2         1         2         3         4         5         6         7         8        "
       " 9        10\n";
  s += " -2        11        12        13        14        15        16        17        18        "
       "19        20\n";
  s += " -3\n";
  for (int step = 1; step <= 2; ++step)
  {
    s += Line(
      "  100CL  10%d%12.5E%12d%20s%2d%5d%-10s%2d", step, 100.0 * step, 20, "", 2, step, "MODAL", 1);
    s += " -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2 "
         "   0\n";
    s += " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n";
    for (int i = 0; i < 20; ++i)
    {
      s += Line(" -1%10d%12.5E%12.5E%12.5E", i + 1, 1.0 * step, 2.0 * step, 3.0 * step);
    }
    s += " -3\n";
    s += Line(
      "  100CL  10%d%12.5E%12d%20s%2d%5d%-10s%2d", step, 100.0 * step, 20, "", 2, step, "MODAL", 1);
    s += " -4  STRESS      6    1\n -5  SXX         1    4    1    1\n -5  SYY         1    4    2 "
         "   2\n";
    s += " -5  SZZ         1    4    3    3\n -5  SXY         1    4    1    2\n";
    s += " -5  SYZ         1    4    2    3\n -5  SZX         1    4    3    1\n";
    for (int i = 0; i < 20; ++i)
    {
      s += Line(" -1%10d%12.5E%12.5E%12.5E%12.5E%12.5E%12.5E",
                i + 1,
                11.0 * step,
                22.0 * step,
                33.0 * step,
                44.0 * step,
                55.0 * step,
                66.0 * step);
    }
    s += " -3\n";
  }
  return s + " 9999\n";
}
} // namespace

int TestAnisoFRDReader(int, char*[])
{
  const std::string file = "TestAnisoFRDReader.frd";
  {
    std::ofstream out(file);
    out << OneHex();
  }
  vtkNew<vtkAnisoFRDReader> reader;
  reader->SetFileName(file.c_str());
  reader->SetStepIndex(1);
  reader->Update();
  vtkUnstructuredGrid* ug = reader->GetOutput();
  AV_CHECK(ug->GetNumberOfPoints() == 20 && ug->GetNumberOfCells() == 1);
  AV_CHECK(reader->GetNumberOfSteps() == 2);
  AV_CHECK(ug->GetNumberOfCells() == 1 && ug->GetCellType(0) == VTK_QUADRATIC_HEXAHEDRON);
  AV_CHECK(WrongMidEdges(ug, 1e-9) == 0);
  vtkDataArray* stress = ug->GetPointData()->GetArray("STRESS");
  AV_CHECK(stress && stress->GetNumberOfComponents() == 6);
  if (stress && stress->GetNumberOfComponents() == 6)
  { // step 2: SXX..SZX = 22 44 66 88 110 132 -> XX YY ZZ XY YZ XZ
    const double expect[6] = { 22, 44, 66, 88, 110, 132 };
    for (int c = 0; c < 6; ++c)
    {
      AV_CHECK(stress->GetComponent(7, c) == expect[c]);
    }
  }
  vtkDataArray* disp = ug->GetPointData()->GetArray("DISP");
  AV_CHECK(disp && disp->GetNumberOfComponents() == 3 && disp->GetComponent(3, 2) == 6.0);
  AV_CHECK(ug->GetPointData()->GetVectors() == disp);
  vtkDataArray* value = ug->GetFieldData()->GetArray("StepValue");
  AV_CHECK(value && value->GetComponent(0, 0) == 200.0);

  reader->ReadAllStepsOn();
  reader->Update();
  AV_CHECK(reader->GetOutput()->GetPointData()->GetArray("STRESS_1") != nullptr);
  AV_CHECK(reader->GetOutput()->GetPointData()->GetArray("DISP_2") != nullptr);
  reader->ReadAllStepsOff();

  vtkNew<av_vtk_test::EventCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetStepIndex(5);
  reader->Update();
  AV_CHECK(errors->Errors == 1);
  reader->SetStepIndex(0);
  reader->SetFileName("/nonexistent/x.frd");
  reader->Update();
  AV_CHECK(errors->Errors == 2);
  {
    std::ofstream out(file);
    const std::string text = OneHex();
    out << text.substr(0, text.size() / 2); // truncated
  }
  reader->SetFileName(file.c_str());
  reader->Update();
  AV_CHECK(errors->Errors == 3);
  std::remove(file.c_str());

  const char* example = "/usr/share/doc/calculix-cgx-examples/examples/result.frd";
  if (std::ifstream(example))
  {
    vtkNew<vtkAnisoFRDReader> real;
    real->SetFileName(example);
    real->SetStepIndex(9);
    real->Update();
    vtkUnstructuredGrid* out = real->GetOutput();
    AV_CHECK(out->GetNumberOfPoints() == 3150 && out->GetNumberOfCells() == 560);
    AV_CHECK(real->GetNumberOfSteps() == 10);
    AV_CHECK(WrongMidEdges(out, 0.05) == 0);
    vtkDataArray* s = out->GetPointData()->GetArray("STRESS");
    AV_CHECK(s && s->GetNumberOfComponents() == 6 && out->GetPointData()->GetTensors() == s);
    vtkDataArray* v = out->GetFieldData()->GetArray("StepValue");
    AV_CHECK(v && v->GetComponent(0, 0) == 6.88120E+04); // mode 10 frequency
  }
  else
  {
    std::cout << "skipping " << example << " (apt-get install calculix-cgx-examples)\n";
  }
  return AV_TEST_RESULT();
}
