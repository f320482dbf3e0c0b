// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoMeditWriter -> vtkAnisoMeditReader round trip: points, tets, refs and a tensor
// metric come back bit for bit; the .sol holds Medit's tensor order; errors do not crash.
#include "vtkAnisoTestUtilities.h" // CHECK, EventCounter, Result
#include "vtkAnisoMeditReader.h"
#include "vtkAnisoMeditWriter.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace
{

std::string Slurp(const std::string& f)
{
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
} // namespace

int TestAnisoMeditReaderWriter(int, char*[])
{
  const double xyz[5][3] = {
    { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0.1, 0.7, 1.0 / 3 }
  };
  vtkNew<vtkUnstructuredGrid> ug;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& p : xyz)
  {
    pts->InsertNextPoint(p);
  }
  ug->SetPoints(pts);
  const vtkIdType t0[4] = { 0, 1, 2, 3 }, t1[4] = { 1, 2, 3, 4 };
  ug->InsertNextCell(VTK_TETRA, 4, t0);
  ug->InsertNextCell(VTK_TETRA, 4, t1);
  vtkNew<vtkIntArray> cref;
  cref->SetName("Ref");
  cref->InsertNextValue(3);
  cref->InsertNextValue(-7);
  ug->GetCellData()->AddArray(cref);
  vtkNew<vtkDoubleArray> metric;
  metric->SetName("Metric");
  metric->SetNumberOfComponents(6);
  for (int i = 0; i < 5; ++i)
  { // all six components distinct, not exactly representable in short decimal
    const double t[6] = { 1 + i / 3.0,    2 + i / 7.0,   3 + i / 11.0,
                          0.4 + i / 13.0, 0.5 / (i + 1), 0.6 / (i + 3) };
    metric->InsertNextTuple(t);
  }
  metric->SetTuple6(0, 1, 2, 3, 4, 5, 6);
  ug->GetPointData()->AddArray(metric);

  const std::string meshFile = "TestAnisoMeditRW.mesh", solFile = "TestAnisoMeditRW.sol";
  vtkNew<vtkAnisoMeditWriter> writer;
  writer->SetInputData(ug);
  writer->SetFileName(meshFile.c_str());
  writer->SetSolFileName(solFile.c_str());
  AV_CHECK(writer->Write() == 1);
  // XX YY ZZ XY YZ XZ = 1 2 3 4 5 6 -> m11 m21 m22 m31 m32 m33 = 1 4 2 6 5 3
  AV_CHECK(Slurp(solFile).find("\n1 4 2 6 5 3\n") != std::string::npos);

  vtkNew<vtkAnisoMeditReader> reader;
  reader->SetFileName(meshFile.c_str());
  reader->SetSolFileName(solFile.c_str());
  reader->Update();
  vtkUnstructuredGrid* out = reader->GetOutput();
  AV_CHECK(out->GetNumberOfPoints() == 5 && out->GetNumberOfCells() == 2);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints() && i < 5; ++i)
  {
    const double* p = out->GetPoint(i);
    AV_CHECK(p[0] == xyz[i][0] && p[1] == xyz[i][1] && p[2] == xyz[i][2]);
  }
  AV_CHECK(out->GetCellType(1) == VTK_TETRA);
  if (out->GetNumberOfCells() == 2)
  {
    const vtkIdType* ids = nullptr;
    vtkIdType n = 0;
    out->GetCellPoints(1, n, ids);
    AV_CHECK(n == 4 && ids[0] == 1 && ids[3] == 4);
  }
  vtkDataArray* rref = out->GetCellData()->GetArray("Ref");
  AV_CHECK(rref && rref->GetComponent(1, 0) == -7);
  vtkDataArray* rm = out->GetPointData()->GetArray("Metric");
  AV_CHECK(rm && rm->GetNumberOfComponents() == 6 && rm->GetNumberOfTuples() == 5);
  if (rm && rm->GetNumberOfComponents() == 6 && rm->GetNumberOfTuples() == 5)
  {
    for (vtkIdType i = 0; i < 5; ++i)
    {
      for (int c = 0; c < 6; ++c)
      {
        AV_CHECK(rm->GetComponent(i, c) == metric->GetComponent(i, c)); // exact
      }
    }
  }

  // 2D triangles: Dimension 2 chosen automatically; a scalar .sol is a size h.
  vtkNew<vtkUnstructuredGrid> tri;
  vtkNew<vtkPoints> tp;
  tp->InsertNextPoint(0, 0, 0);
  tp->InsertNextPoint(1, 0, 0);
  tp->InsertNextPoint(0, 1, 0);
  tri->SetPoints(tp);
  tri->InsertNextCell(VTK_TRIANGLE, 3, t0);
  writer->SetInputData(tri);
  writer->SetSolFileName("");
  AV_CHECK(writer->Write() == 1);
  AV_CHECK(Slurp(meshFile).find("Dimension 2") != std::string::npos);
  {
    std::ofstream sol(solFile);
    sol << "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 1\n0.5\n0.25\n1\nEnd\n";
  }
  reader->Modified();
  reader->Update();
  rm = reader->GetOutput()->GetPointData()->GetArray("Metric");
  AV_CHECK(rm && rm->GetComponent(0, 0) == 4.0 && rm->GetComponent(1, 1) == 16.0 &&
        rm->GetComponent(1, 3) == 0.0);
  AV_CHECK(reader->GetOutput()->GetPointData()->GetArray("Size") != nullptr);
  AV_CHECK(reader->GetOutput()->GetCellType(0) == VTK_TRIANGLE);

  // errors: reported, not crashed
  vtkNew<av_vtk_test::EventCounter> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName("/nonexistent/x.mesh");
  reader->Update();
  AV_CHECK(errors->Errors >= 1 && reader->GetOutput()->GetNumberOfPoints() == 0);
  {
    std::ofstream bad(meshFile);
    bad << "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 zz 0\nEnd\n";
  }
  const int before = errors->Errors;
  reader->SetFileName(meshFile.c_str());
  reader->SetSolFileName("");
  reader->Update();
  AV_CHECK(errors->Errors > before);
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetFileName("/nonexistent/dir/x.mesh");
  AV_CHECK(writer->Write() == 0);

  std::remove(meshFile.c_str());
  std::remove(solFile.c_str());
  return AV_TEST_RESULT();
}
