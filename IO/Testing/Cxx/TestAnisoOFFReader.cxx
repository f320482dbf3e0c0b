// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoOFFReader: a quad and a triangle (the quad fanned into two triangles) with a comment
// and the header on the counts' line, double-precision points, and the error paths (no file
// name, missing file, index out of range): one error each, an empty output, no crash.
#include "vtkAnisoOFFReader.h"
#include "vtkAnisoTestUtilities.h" // AV_CHECK, EventCounter

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <fstream>
#include <string>

int TestAnisoOFFReader(int, char*[])
{
  const std::string file = "TestAnisoOFFReader.off";
  {
    std::ofstream out(file);
    out << "OFF 5 2 0\n# a unit quad and a triangle above it\n"
           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.1 0.2 0.30000000000000004\n"
           "4 0 1 2 3\n3 0 1 4 255 0 0\n";
  }
  vtkNew<vtkAnisoOFFReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* pd = reader->GetOutput();
  AV_CHECK(pd->GetNumberOfPoints() == 5 && pd->GetNumberOfPolys() == 3);
  AV_CHECK(pd->GetPoints()->GetDataType() == VTK_DOUBLE);
  AV_CHECK(pd->GetPoint(4)[2] == 0.30000000000000004);
  vtkNew<vtkIdList> ids;
  pd->GetPolys()->GetCellAtId(2, ids);
  AV_CHECK(
    ids->GetNumberOfIds() == 3 && ids->GetId(0) == 0 && ids->GetId(1) == 1 && ids->GetId(2) == 4);
  for (vtkIdType c = 0; c < 2; ++c)
  {
    pd->GetPolys()->GetCellAtId(c, ids);
    AV_CHECK(ids->GetNumberOfIds() == 3 && ids->GetId(0) == 0); // fanned from vertex 0
  }

  vtkNew<av_vtk_test::EventCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName("/nonexistent/x.off");
  reader->Update();
  AV_CHECK(errors->Errors == 1 && reader->GetOutput()->GetNumberOfPoints() == 0);
  {
    std::ofstream out(file);
    out << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  }
  reader->SetFileName(file.c_str());
  reader->Update();
  AV_CHECK(errors->Errors == 2 && reader->GetOutput()->GetNumberOfPolys() == 0);
  vtkNew<vtkAnisoOFFReader> unnamed;
  unnamed->AddObserver(vtkCommand::ErrorEvent, errors);
  unnamed->Update();
  AV_CHECK(errors->Errors == 3);
  std::remove(file.c_str());
  return AV_TEST_RESULT();
}
