// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkAnisoTensorToMetric: eigen-structure of the produced metric, negative eigenvalues,
// the global scale, symmetrization of 9-component input, cell tensors averaged to points,
// smoothing along cell edges, 2D detection, errors, and that the input is left unmodified.
#include "vtkAnisoTensorToMetric.h"
#include "vtkAnisoTestUtilities.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

namespace
{
using av_vtk_test::EventCounter;
using av_vtk_test::FieldValue;
using av_vtk_test::Watch;

/// Rotation about the unit axis (1, 2, 3) / |.| by 0.7 rad.
void Rotation(double r[3][3])
{
  double axis[3] = { 1, 2, 3 };
  vtkMath::Normalize(axis);
  const double a = 0.7, c = std::cos(a), s = std::sin(a);
  const double x = axis[0], y = axis[1], z = axis[2];
  const double m[3][3] = {
    { c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s },
    { y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s },
    { z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c) }
  };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r[i][j] = m[i][j];
}

/// T = R diag(l) R^T as a full 3x3.
void Compose(const double r[3][3], const double l[3], double t[3][3])
{
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      t[i][j] = 0;
      for (int k = 0; k < 3; ++k)
        t[i][j] += r[i][k] * l[k] * r[j][k];
    }
}

void Pack6(const double t[3][3], double* v)
{
  v[0] = t[0][0];
  v[1] = t[1][1];
  v[2] = t[2][2];
  v[3] = t[0][1];
  v[4] = t[1][2];
  v[5] = t[0][2];
}

vtkSmartPointer<vtkImageData> MakeGrid(int nx, int ny, int nz)
{
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(nx, ny, nz);
  grid->SetSpacing(0.5, 0.5, 0.5);
  return grid;
}

/// The conversion alone: no gradation, no normalization (the tests of the conversion).
void NoPreparation(vtkAnisoTensorToMetric* filter)
{
  filter->GradationOff();
  filter->SetNumberOfSites(0);
}

vtkSmartPointer<vtkDoubleArray> MakeTensors(const char* name, vtkIdType n, int comps)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(comps);
  a->SetNumberOfTuples(n);
  return a;
}

/// Eigenvalues (ascending) and eigenvectors (columns) of a 6-component tuple.
void Eigen6(const double* v, double w[3], double vec[3][3])
{
  double m[3][3];
  vtkMath::TensorFromSymmetricTensor(v, &m[0][0]);
  double a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      a[i][j] = m[i][j];
  double vecT[3][3];
  vtkMath::Diagonalize3x3(a, w, vecT); // columns are eigenvectors, unsorted
  int order[3] = { 0, 1, 2 };
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (w[order[j]] < w[order[i]])
        std::swap(order[i], order[j]);
  double ws[3];
  for (int k = 0; k < 3; ++k)
  {
    ws[k] = w[order[k]];
    for (int i = 0; i < 3; ++i)
      vec[i][k] = vecT[i][order[k]];
  }
  for (int k = 0; k < 3; ++k)
    w[k] = ws[k];
}

// A rotated anisotropic tensor, scaled per point: the metric must have eigenvalues
// c * (s * l)^2 along the same eigenvectors, c = 1 / smallest, and the input must be untouched.
void TestRotatedTensor(EventCounter* events)
{
  auto grid = MakeGrid(4, 3, 3);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto tensors = MakeTensors("Stress", n, 6);
  double r[3][3];
  Rotation(r);
  const double base[3] = { 0.5, 1.0, 2.0 };
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double s = 1.0 + static_cast<double>(i) / (n - 1); // s in [1, 2]
    const double l[3] = { s * base[0], s * base[1], s * base[2] };
    double t[3][3], v[6];
    Compose(r, l, t);
    Pack6(t, v);
    tensors->SetTypedTuple(i, v);
  }
  grid->GetPointData()->SetTensors(tensors);
  const double before = tensors->GetComponent(7, 3);

  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  filter->SetMaximumAnisotropy(0); // no cap
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Errors == 0 && events->Warnings == 0);
  vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  vtkDataArray* metric = out->GetPointData()->GetArray("Metric");
  AV_CHECK(metric && metric->GetNumberOfComponents() == 6);
  AV_CHECK(out->GetPointData()->GetTensors() == metric);
  AV_CHECK(filter->GetUsedDimension() == 3);
  // Smallest eigenvalue of the field: (1 * 0.5)^2 = 0.25 -> c = 4.
  AV_CHECK_NEAR(filter->GetMetricScale(), 4.0, 1e-10);
  AV_CHECK_NEAR(FieldValue(out, "MetricScale"), 4.0, 1e-10);
  AV_CHECK_NEAR(FieldValue(out, "StretchMax"), 4.0, 1e-9);
  double globalMin = 1e300;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double s = 1.0 + static_cast<double>(i) / (n - 1);
    double v[6], w[3], vec[3][3];
    metric->GetTuple(i, v);
    Eigen6(v, w, vec);
    for (int k = 0; k < 3; ++k)
    {
      const double expected = 4.0 * (s * base[k]) * (s * base[k]);
      AV_CHECK_NEAR(w[k], expected, 1e-9 * expected);
      // Eigenvector k is column k of R (up to sign).
      const double dot = vec[0][k] * r[0][k] + vec[1][k] * r[1][k] + vec[2][k] * r[2][k];
      AV_CHECK_NEAR(std::abs(dot), 1.0, 1e-9);
    }
    globalMin = std::min(globalMin, w[0]);
    AV_CHECK_NEAR(out->GetPointData()->GetArray("Stretch")->GetTuple1(i), 4.0, 1e-9);
  }
  AV_CHECK_NEAR(globalMin, 1.0, 1e-10);

  // The input is unmodified.
  AV_CHECK(grid->GetPointData()->GetNumberOfArrays() == 1);
  AV_CHECK(grid->GetPointData()->GetArray("Metric") == nullptr);
  AV_CHECK(grid->GetFieldData()->GetNumberOfArrays() == 0);
  AV_CHECK(tensors->GetComponent(7, 3) == before);
  AV_CHECK(grid->GetPointData()->GetTensors() == tensors);
}

// Negative eigenvalues: ABSOLUTE gives an SPD metric from |lambda|; CLAMP gives the floor to
// the compressive direction.
void TestNegativeEigenvalues(EventCounter* events)
{
  auto grid = MakeGrid(3, 3, 3);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto tensors = MakeTensors("Stress", n, 6);
  double r[3][3];
  Rotation(r);
  const double l[3] = { -3.0, 1.0, 2.0 };
  double t[3][3], v[6];
  Compose(r, l, t);
  Pack6(t, v);
  for (vtkIdType i = 0; i < n; ++i)
    tensors->SetTypedTuple(i, v);
  grid->GetPointData()->SetTensors(tensors);

  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  filter->SetMaximumAnisotropy(0);
  filter->SetEigenvalueModeToAbsolute();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  AV_CHECK(filter->GetNumberOfNegativeTuples() == n);
  AV_CHECK_NEAR(FieldValue(out, "NumNegative"), static_cast<double>(n), 0);
  double w[3], vec[3][3];
  out->GetPointData()->GetArray("Metric")->GetTuple(0, v);
  Eigen6(v, w, vec);
  // |lambda|^2 = 9, 1, 4, scaled by c = 1: ascending 1, 4, 9; the largest along R's column 0.
  AV_CHECK(w[0] > 0);
  AV_CHECK_NEAR(w[0], 1.0, 1e-9);
  AV_CHECK_NEAR(w[1], 4.0, 1e-9);
  AV_CHECK_NEAR(w[2], 9.0, 1e-9);
  AV_CHECK_NEAR(std::abs(vec[0][2] * r[0][0] + vec[1][2] * r[1][0] + vec[2][2] * r[2][0]), 1.0, 1e-9);

  filter->SetEigenvalueModeToClamp();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  out->GetPointData()->GetArray("Metric")->GetTuple(0, v);
  Eigen6(v, w, vec);
  // The compressive direction (R's column 0) now has the smallest eigenvalue (the floor).
  AV_CHECK(w[0] > 0);
  AV_CHECK_NEAR(std::abs(vec[0][0] * r[0][0] + vec[1][0] * r[1][0] + vec[2][0] * r[2][0]), 1.0, 1e-9);
  AV_CHECK(filter->GetNumberOfClampedTuples() == n);
  AV_CHECK_NEAR(w[0], 1.0, 1e-9); // the global scale makes the floor 1
  AV_CHECK(w[2] > 1e5);           // 2 / (3e-3): floor relative to max |lambda| = 3, squared
  AV_CHECK(events->Errors == 0);
}

// 9 components, non-symmetric: same metric as the symmetric part, with a warning.
void TestNonSymmetric(EventCounter* events)
{
  auto grid = MakeGrid(3, 3, 3);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto sym = MakeTensors("Sym", n, 6);
  auto full = MakeTensors("Full", n, 9);
  double r[3][3];
  Rotation(r);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double l[3] = { 1.0 + 0.1 * i, 2.0, 3.0 };
    double t[3][3], v[6];
    Compose(r, l, t);
    Pack6(t, v);
    sym->SetTypedTuple(i, v);
    const double a[3] = { 0.3, -0.2, 0.1 }; // antisymmetric part
    const double f[9] = { t[0][0],
      t[0][1] + a[0],
      t[0][2] + a[1],
      t[1][0] - a[0],
      t[1][1],
      t[1][2] + a[2],
      t[2][0] - a[1],
      t[2][1] - a[2],
      t[2][2] };
    full->SetTypedTuple(i, f);
  }
  grid->GetPointData()->AddArray(sym);
  grid->GetPointData()->AddArray(full);

  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  filter->SetInputData(grid);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Sym");
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Warnings == 0);
  vtkNew<vtkDoubleArray> reference;
  reference->DeepCopy(
    vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("Metric"));

  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Full");
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Warnings == 1);
  AV_CHECK(events->Last.find("not symmetric") != std::string::npos);
  AV_CHECK(filter->GetMaxAsymmetry() > 0.01);
  vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  AV_CHECK(FieldValue(out, "MaxAsymmetry") > 0.01);
  vtkDataArray* metric = out->GetPointData()->GetArray("Metric");
  double maxDiff = 0;
  for (vtkIdType i = 0; i < n; ++i)
    for (int k = 0; k < 6; ++k)
      maxDiff =
        std::max(maxDiff, std::abs(metric->GetComponent(i, k) - reference->GetComponent(i, k)));
  AV_CHECK(maxDiff < 1e-10);
}

// Cell tensors are averaged to the points: with TensorAsMetric, no cap and no scale, an SPD
// tensor is its own metric, so shared points get the mean of their cells' tensors.
void TestCellTensors(EventCounter* events)
{
  auto grid = MakeGrid(3, 2, 2); // two voxels sharing the face x = 0.5
  auto tensors = MakeTensors("CellT", 2, 6);
  const double a[6] = { 1, 1, 1, 0, 0, 0 };
  const double b[6] = { 3, 5, 7, 0.5, 0, 0 };
  tensors->SetTypedTuple(0, a);
  tensors->SetTypedTuple(1, b);
  grid->GetCellData()->SetTensors(tensors); // no point tensors: cell tensors are the default

  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  filter->SetInterpretationToTensorAsMetric();
  filter->SetMaximumAnisotropy(0);
  filter->ApplyGlobalScaleOff();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Errors == 0);
  vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  vtkDataArray* metric = out->GetPointData()->GetArray("Metric");
  AV_CHECK(metric && metric->GetNumberOfTuples() == 12);
  for (vtkIdType p = 0; p < 12; ++p)
  {
    const double x = out->GetPoint(p)[0];
    for (int k = 0; k < 6; ++k)
    {
      const double expected = x < 0.25 ? a[k] : (x > 0.75 ? b[k] : 0.5 * (a[k] + b[k]));
      AV_CHECK_NEAR(metric->GetComponent(p, k), expected, 1e-12);
    }
  }
}

// Smoothing follows the cell edges: after one iteration an edge neighbor of the perturbed
// point changes, a face-diagonal neighbor does not.
void TestSmoothingEdges(EventCounter* events)
{
  auto grid = MakeGrid(3, 3, 3);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto tensors = MakeTensors("T", n, 6);
  const double id[6] = { 1, 1, 1, 0, 0, 0 };
  const double big[6] = { 4, 4, 4, 0, 0, 0 };
  for (vtkIdType i = 0; i < n; ++i)
    tensors->SetTypedTuple(i, i == 13 ? big : id); // 13 = the center point (1, 1, 1)
  grid->GetPointData()->SetTensors(tensors);

  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  filter->SetInterpretationToTensorAsMetric();
  filter->SetMaximumAnisotropy(0);
  filter->ApplyGlobalScaleOff();
  filter->SetSmoothingIterations(1);
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  vtkDataArray* metric =
    vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("Metric");
  const vtkIdType edgeNeighbor = 13 + 1;     // (2, 1, 1)
  const vtkIdType diagonalNeighbor = 13 + 4; // (2, 2, 1): a face diagonal of a voxel
  const vtkIdType corner = 0;
  AV_CHECK(metric->GetComponent(edgeNeighbor, 0) > 1.01);
  AV_CHECK_NEAR(metric->GetComponent(diagonalNeighbor, 0), 1.0, 1e-12);
  AV_CHECK_NEAR(metric->GetComponent(corner, 0), 1.0, 1e-12);
  AV_CHECK(metric->GetComponent(13, 0) < 3.99);
  AV_CHECK(events->Errors == 0);
}

// A flat grid (z = const) is 2D: ZZ, YZ, XZ are zero.
void TestFlat(EventCounter* events)
{
  auto grid = MakeGrid(4, 4, 1);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto tensors = MakeTensors("T", n, 6);
  const double t[6] = { 2, 1, 5, 0.3, 0.7, 0.2 };
  for (vtkIdType i = 0; i < n; ++i)
    tensors->SetTypedTuple(i, t);
  grid->GetPointData()->SetTensors(tensors);
  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(filter->GetUsedDimension() == 2);
  vtkDataArray* metric =
    vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("Metric");
  AV_CHECK(metric->GetComponent(3, 2) == 0 && metric->GetComponent(3, 4) == 0 &&
    metric->GetComponent(3, 5) == 0);
  AV_CHECK(metric->GetComponent(3, 0) > 0 && metric->GetComponent(3, 1) > 0);
  filter->SetDimensionTo3D();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  metric =
    vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("Metric");
  AV_CHECK(metric->GetComponent(3, 2) > 0);
}

// Errors: NaN, wrong component count, all zero, a missing named array.
void TestErrors(EventCounter* events)
{
  auto grid = MakeGrid(3, 3, 3);
  const vtkIdType n = grid->GetNumberOfPoints();
  vtkNew<vtkAnisoTensorToMetric> filter;
  NoPreparation(filter); // these tests check the conversion itself
  Watch(filter, events);
  filter->SetInputData(grid);

  auto tensors = MakeTensors("T", n, 6);
  const double t[6] = { 2, 1, 5, 0.3, 0.7, 0.2 };
  for (vtkIdType i = 0; i < n; ++i)
    tensors->SetTypedTuple(i, t);
  tensors->SetComponent(5, 1, std::nan(""));
  grid->GetPointData()->SetTensors(tensors);
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 0);
  AV_CHECK(events->Errors >= 1);

  auto vectors = MakeTensors("V", n, 3);
  vectors->Fill(1.0);
  grid->GetPointData()->AddArray(vectors);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "V");
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 0);
  AV_CHECK(events->Errors >= 1);
  grid->Modified();

  auto zeros = MakeTensors("Z", n, 9);
  zeros->Fill(0.0);
  grid->GetPointData()->AddArray(zeros);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Z");
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 0);
  AV_CHECK(events->Errors >= 1);

  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Missing");
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 0);
  AV_CHECK(events->Errors >= 1);
}
}

// Metric preparation through the filter, on an isotropic stress whose size jumps 1000x across
// x = 2.5 (voxels of side 0.5): normalized to the sites, graded along every grid edge (for
// isotropic metrics the bound reads lambda_q >= lambda_p / (1 + |e| sqrt(lambda_p) ln beta)^2),
// the figures and RawMetric reported; uniform mode equalizes the sizes; hmax holds.
void TestPreparation(EventCounter* events)
{
  const int nx = 11;
  auto grid = MakeGrid(nx, nx, nx);
  const vtkIdType n = grid->GetNumberOfPoints();
  auto tensors = MakeTensors("Stress", n, 6);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = grid->GetPoint(i)[0] < 2.5 ? 1000.0 : 1.0;
    const double t[6] = { v, v, v, 0, 0, 0 };
    tensors->SetTypedTuple(i, t);
  }
  grid->GetPointData()->SetTensors(tensors);
  vtkNew<vtkAnisoTensorToMetric> filter;
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(grid);
  filter->SetMinimumEigenvalue(1e-4);
  filter->SetNumberOfSites(500);
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Errors == 0);
  vtkDataSet* out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  vtkDataArray* metric = out->GetPointData()->GetArray("Metric");
  AV_CHECK(out->GetPointData()->GetArray("RawMetric") != nullptr);
  AV_CHECK_NEAR(FieldValue(out, "ImpliedSites"), 500.0, 500.0 * 2.5e-3);
  AV_CHECK_NEAR(filter->GetImpliedSites(), 500.0, 500.0 * 2.5e-3);
  AV_CHECK(FieldValue(out, "NumGraded") > 0 && filter->GetNumberOfGradedPoints() > 0);
  AV_CHECK(filter->GetPercentile95Change() > 0.5); // a 1000x jump is not kept as it is
  AV_CHECK(FieldValue(out, "MetricPrepP95Change") == filter->GetPercentile95Change());
  // The output keeps the conversion's scale (ApplyGlobalScale); the bound is in cell units.
  const double cellUnits = FieldValue(out, "CellUnitScale");
  AV_CHECK(cellUnits > 0.0 && cellUnits != 1.0);
  const double lnBeta = std::log(filter->GetGradationFactor());
  double worst = 0.0;
  for (int k = 0; k < nx; ++k)
    for (int j = 0; j < nx; ++j)
      for (int i = 0; i < nx; ++i)
      {
        const vtkIdType p = (k * nx + j) * nx + i;
        const vtkIdType neighbors[3] = { i + 1 < nx ? p + 1 : -1, j + 1 < nx ? p + nx : -1,
          k + 1 < nx ? p + nx * nx : -1 };
        for (vtkIdType q : neighbors)
        {
          if (q < 0)
            continue;
          const double lp = cellUnits * metric->GetComponent(p, 0);
          const double lq = cellUnits * metric->GetComponent(q, 0);
          for (const auto& [a, b] : { std::pair<double, double>(lp, lq), { lq, lp } })
          {
            const double grow = 1.0 + 0.5 * std::sqrt(a) * lnBeta;
            worst = std::max(worst, a / (grow * grow) / b);
          }
        }
      }
  AV_CHECK_MSG(worst <= 1.0 + 1e-5, "gradation bound along the grid edges: " << worst);
  // The input kept its tensors and gained nothing.
  AV_CHECK(grid->GetPointData()->GetNumberOfArrays() == 1);

  filter->SetSizeModeToUniform();
  filter->GradationOff();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  metric = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0))->GetPointData()->GetArray("Metric");
  for (vtkIdType i = 1; i < n; ++i)
    AV_CHECK_NEAR(metric->GetComponent(i, 0) / metric->GetComponent(0, 0), 1.0, 1e-9);

  filter->SetSizeModeToTensor();
  filter->GradationOn();
  filter->SetHMax(0.3);
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  out = vtkDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  metric = out->GetPointData()->GetArray("Metric");
  for (vtkIdType i = 0; i < n; ++i)
    AV_CHECK(FieldValue(out, "CellUnitScale") * metric->GetComponent(i, 0) >=
      (1.0 - 1e-9) / (0.3 * 0.3));
  AV_CHECK(events->Errors == 0);
}

int TestAnisoTensorToMetric(int, char*[])
{
  vtkNew<EventCounter> events;
  TestRotatedTensor(events);
  TestNegativeEigenvalues(events);
  TestNonSymmetric(events);
  TestCellTensors(events);
  TestSmoothingEdges(events);
  TestFlat(events);
  TestErrors(events);
  TestPreparation(events);
  return AV_TEST_RESULT();
}
