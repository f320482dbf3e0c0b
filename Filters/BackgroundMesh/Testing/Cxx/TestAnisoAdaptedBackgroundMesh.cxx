// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkAnisoAdaptedBackgroundMesh on a tet grid with a wall-layer metric: the output is
// refined and keeps the volume, its metric array is the kernel's SPD interpolation (6 and 9
// components), a linear point field stays exact, cell data follows the parent cell, the input
// is not modified, the figures reach the field data; bad input fails with an error.
#include "vtkAnisoAdaptedBackgroundMesh.h"
#include "vtkAnisoTestUtilities.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkTetra.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>

namespace
{
using av_vtk_test::EventCounter;
using av_vtk_test::FieldValue;
using av_vtk_test::Watch;

double Field(const double x[3])
{
  return 1.0 - 2.0 * x[0] + 0.5 * x[1] + 3.0 * x[2];
}

/// n^3 points on [0,1]^3, 6 tets per cube (Kuhn split), point data "Metric" (a wall layer at
/// z = 0; 6 or 9 components), "F" (linear), cell data "Material" (the cube index).
vtkSmartPointer<vtkUnstructuredGrid> MakeGrid(int n, int metricComponents)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> metric, f;
  metric->SetName("Metric");
  metric->SetNumberOfComponents(metricComponents);
  f->SetName("F");
  const double h = 1.0 / (n - 1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x[3] = { i * h, j * h, k * h };
        points->InsertNextPoint(x);
        const double hz = 0.05 + 0.3 * x[2], hxy = 0.2;
        const double a = 1.0 / (hxy * hxy), c = 1.0 / (hz * hz);
        if (metricComponents == 6)
          metric->InsertNextTuple6(a, a, c, 0, 0, 0);
        else
        {
          const double t[9] = { a, 0, 0, 0, a, 0, 0, 0, c };
          metric->InsertNextTuple(t);
        }
        f->InsertNextValue(Field(x));
      }
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(metric);
  grid->GetPointData()->AddArray(f);
  vtkNew<vtkIntArray> material;
  material->SetName("Material");
  // The 6 tets of the Kuhn split of a cube along the main diagonal 0-7.
  const int tets[6][4] = {
    { 0, 1, 3, 7 }, { 0, 1, 7, 5 }, { 0, 2, 7, 3 }, { 0, 2, 6, 7 }, { 0, 4, 5, 7 }, { 0, 4, 7, 6 }
  };
  auto id = [n](int i, int j, int k) { return static_cast<vtkIdType>(i + n * (j + n * k)); };
  int cube = 0;
  for (int k = 0; k + 1 < n; ++k)
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i, ++cube)
      {
        vtkIdType corner[8];
        for (int c = 0; c < 8; ++c)
          corner[c] = id(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        for (const auto& t : tets)
        {
          vtkIdType ids[4] = { corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]] };
          double p[4][3];
          for (int q = 0; q < 4; ++q)
            points->GetPoint(ids[q], p[q]);
          if (vtkTetra::ComputeVolume(p[0], p[1], p[2], p[3]) < 0)
            std::swap(ids[2], ids[3]);
          grid->InsertNextCell(VTK_TETRA, 4, ids);
          material->InsertNextValue(cube);
        }
      }
  grid->GetCellData()->AddArray(material);
  return grid;
}

double Volume(vtkUnstructuredGrid* g, double& minVolume)
{
  double sum = 0.0;
  minVolume = 1e300;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c)
  {
    g->GetCellPoints(c, ids);
    double p[4][3];
    for (int q = 0; q < 4; ++q)
      g->GetPoint(ids->GetId(q), p[q]);
    const double v = vtkTetra::ComputeVolume(p[0], p[1], p[2], p[3]);
    sum += v;
    minVolume = std::min(minVolume, v);
  }
  return sum;
}

void CheckOutput(vtkUnstructuredGrid* input, vtkUnstructuredGrid* out, int components)
{
  AV_CHECK(out->GetNumberOfPoints() > 2 * input->GetNumberOfPoints());
  double minVolume = 0.0;
  AV_CHECK_NEAR(Volume(out, minVolume), 1.0, 1e-12);
  AV_CHECK(minVolume > 0.0);
  vtkDataArray* metric = out->GetPointData()->GetArray("Metric");
  vtkDataArray* f = out->GetPointData()->GetArray("F");
  AV_CHECK(metric && metric->GetNumberOfComponents() == components && f);
  AV_CHECK(out->GetPointData()->GetTensors() == metric);
  if (!metric || !f)
    return;
  bool spd = true;
  double worstField = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double t[9];
    metric->GetTuple(i, t);
    double m[3][3];
    if (components == 6)
      vtkMath::TensorFromSymmetricTensor(t, m[0]);
    else
      for (int r = 0; r < 9; ++r)
        m[r / 3][r % 3] = t[r];
    // Sylvester: leading minors positive.
    const double d1 = m[0][0], d2 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    spd = spd && d1 > 0 && d2 > 0 && vtkMath::Determinant3x3(m) > 0 && m[0][1] == m[1][0];
    worstField = std::max(worstField, std::abs(f->GetTuple1(i) - Field(out->GetPoint(i))));
  }
  AV_CHECK(spd);
  AV_CHECK_NEAR(worstField, 0.0, 1e-11);
  vtkDataArray* material = out->GetCellData()->GetArray("Material");
  vtkDataArray* parent = out->GetCellData()->GetArray("ParentCellId");
  AV_CHECK(material && parent);
  bool follows = material && parent;
  for (vtkIdType c = 0; follows && c < out->GetNumberOfCells(); ++c)
    follows = material->GetTuple1(c) ==
      input->GetCellData()
        ->GetArray("Material")
        ->GetTuple1(static_cast<vtkIdType>(parent->GetTuple1(c)));
  AV_CHECK(follows);
  AV_CHECK(FieldValue(out, "BackgroundMaxEdgeLength") <= 0.5 + 1e-12);
  AV_CHECK(FieldValue(out, "BackgroundSplits") > 0);
  AV_CHECK(FieldValue(out, "BackgroundInputPoints") == input->GetNumberOfPoints());
}
} // namespace

int TestAnisoAdaptedBackgroundMesh(int, char*[])
{
  vtkNew<EventCounter> events;
  for (const int components : { 6, 9 })
  {
    vtkSmartPointer<vtkUnstructuredGrid> input = MakeGrid(4, components);
    const vtkIdType inputPoints = input->GetNumberOfPoints();
    const double firstMetric = input->GetPointData()->GetArray("Metric")->GetComponent(5, 2);
    vtkNew<vtkAnisoAdaptedBackgroundMesh> filter;
    Watch(filter, events);
    filter->SetInputData(input);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
    filter->SetNumberOfSites(200);
    filter->SetTargetEdgeLength(0.5);
    filter->Update();
    AV_CHECK(events->Errors == 0);
    CheckOutput(input, filter->GetOutput(), components);
    AV_CHECK(FieldValue(filter->GetOutput(), "BackgroundAdapted") == 1.0);
    // The input is untouched.
    AV_CHECK(input->GetNumberOfPoints() == inputPoints);
    AV_CHECK(input->GetPointData()->GetArray("Metric")->GetComponent(5, 2) == firstMetric);
  }
  // OnlyWhenCoarse: a grid coarser than the output is adapted, one finer than it (few sites)
  // passes through with its own points and data.
  {
    vtkSmartPointer<vtkUnstructuredGrid> input = MakeGrid(4, 6);
    vtkNew<vtkAnisoAdaptedBackgroundMesh> filter;
    events->Reset();
    Watch(filter, events);
    filter->SetInputData(input);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
    filter->OnlyWhenCoarseOn();
    filter->SetNumberOfSites(2000);
    filter->Update();
    AV_CHECK(events->Errors == 0);
    AV_CHECK(filter->GetInputMeanEdgeLength() > 1.0);
    AV_CHECK(filter->GetAdapted());
    AV_CHECK(filter->GetOutput()->GetNumberOfPoints() > input->GetNumberOfPoints());
    filter->SetNumberOfSites(5);
    filter->Update();
    AV_CHECK(events->Errors == 0);
    AV_CHECK(filter->GetInputMeanEdgeLength() < 1.0);
    AV_CHECK(!filter->GetAdapted());
    vtkUnstructuredGrid* out = filter->GetOutput();
    AV_CHECK(FieldValue(out, "BackgroundAdapted") == 0.0);
    AV_CHECK(out->GetNumberOfPoints() == input->GetNumberOfPoints());
    AV_CHECK(out->GetNumberOfCells() == input->GetNumberOfCells());
    bool same = out->GetNumberOfPoints() == input->GetNumberOfPoints();
    for (vtkIdType i = 0; same && i < out->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      out->GetPoint(i, a);
      input->GetPoint(i, b);
      same = a[0] == b[0] && a[1] == b[1] && a[2] == b[2] &&
        out->GetPointData()->GetArray("F")->GetTuple1(i) ==
          input->GetPointData()->GetArray("F")->GetTuple1(i) &&
        out->GetPointData()->GetArray("Metric")->GetComponent(i, 2) ==
          input->GetPointData()->GetArray("Metric")->GetComponent(i, 2);
    }
    AV_CHECK(same);
  }
  // No metric array: a clear error, no output.
  {
    vtkSmartPointer<vtkUnstructuredGrid> input = MakeGrid(3, 6);
    input->GetPointData()->RemoveArray("Metric");
    vtkNew<vtkAnisoAdaptedBackgroundMesh> filter;
    events->Reset();
    Watch(filter, events);
    filter->SetInputData(input);
    filter->Update();
    AV_CHECK(events->Errors >= 1);
    AV_CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  }
  // A metric that is not positive definite: the kernel's message.
  {
    vtkSmartPointer<vtkUnstructuredGrid> input = MakeGrid(3, 6);
    input->GetPointData()->GetArray("Metric")->SetComponent(4, 0, -1.0);
    vtkNew<vtkAnisoAdaptedBackgroundMesh> filter;
    events->Reset();
    Watch(filter, events);
    filter->SetInputData(input);
    filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Metric");
    filter->Update();
    AV_CHECK(events->Errors >= 1);
    AV_CHECK_MSG(events->All.find("positive") != std::string::npos, events->All);
  }
  return AV_TEST_RESULT();
}
