// SPDX-License-Identifier: BSD-3-Clause
// vtkAnisoRestrictedDelaunay's repair of inverted elements: a unit square folded in an 8D
// embedding with 60 random sites has inverted triangles. With RepairInverted off they are
// reported; with it on none is left (checked by the input-space signed areas, not only the
// filter's flag), the input sites come first and unchanged, and the inserted sites carry their
// own CellId / Barycentric and point data interpolated from the mesh (Metric, Embedding).
#include "vtkAnisoRestrictedDelaunay.h"
#include "vtkAnisoTestUtilities.h"

#include <vtkCellArray.h>
#include <vtkDataObject.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <cstdio>
#include <random>

using av_vtk_test::EventCounter;
using av_vtk_test::FieldValue;

namespace
{
constexpr int N = 33;   // grid vertices per side
constexpr int Dim = 8;  // embedding dimension
constexpr int Sites = 60;

void EmbeddingAt(double x, double y, double* e)
{
  e[0] = x;
  e[1] = y;
  for (int c = 2; c < Dim; ++c)
  {
    switch (c % 3)
    {
      case 0: e[c] = 0.2 * std::sin(12.0 * x + 0.3 * c); break;
      case 1: e[c] = 0.2 * std::cos(12.0 * y); break;
      default: e[c] = 0.2 * std::sin(12.0 * (x + y)); break;
    }
  }
}

// Unit square, two counter-clockwise triangles per quad, "Embedding" and "Metric" point data.
vtkNew<vtkUnstructuredGrid> MakeMesh()
{
  vtkNew<vtkUnstructuredGrid> mesh;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> embedding, metric;
  embedding->SetName("Embedding");
  embedding->SetNumberOfComponents(Dim);
  metric->SetName("Metric");
  metric->SetNumberOfComponents(6);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const double x = double(i) / (N - 1), y = double(j) / (N - 1);
      points->InsertNextPoint(x, y, 0.0);
      double e[Dim];
      EmbeddingAt(x, y, e);
      embedding->InsertNextTuple(e);
      const double m[6] = { 1.0 + x, 2.0 + y, 1.0, 0.1 * x * y, 0.0, 0.0 };
      metric->InsertNextTuple(m);
    }
  mesh->SetPoints(points);
  mesh->GetPointData()->AddArray(embedding);
  mesh->GetPointData()->AddArray(metric);
  mesh->AllocateExact((N - 1) * (N - 1) * 2, 3);
  for (int j = 0; j + 1 < N; ++j)
    for (int i = 0; i + 1 < N; ++i)
    {
      const vtkIdType a = j * N + i, b = a + 1, c = a + N, d = c + 1;
      const vtkIdType t0[3] = { a, b, d }, t1[3] = { a, d, c };
      mesh->InsertNextCell(VTK_TRIANGLE, 3, t0);
      mesh->InsertNextCell(VTK_TRIANGLE, 3, t1);
    }
  return mesh;
}

// Random sites as the particle sampler writes them (CellId, Barycentric, Embedding, Metric).
vtkNew<vtkPolyData> MakeSites(vtkUnstructuredGrid* mesh)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  vtkNew<vtkPolyData> sites;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkIntArray> cellIds;
  cellIds->SetName("CellId");
  vtkNew<vtkDoubleArray> bary, embedding, metric;
  bary->SetName("Barycentric");
  bary->SetNumberOfComponents(4);
  embedding->SetName("Embedding");
  embedding->SetNumberOfComponents(Dim);
  metric->SetName("Metric");
  metric->SetNumberOfComponents(6);
  vtkNew<vtkIdList> ids;
  for (int s = 0; s < Sites; ++s)
  {
    const vtkIdType c = static_cast<vtkIdType>(rng() % mesh->GetNumberOfCells());
    double b[4] = { 0, 0, 0, 0 }, sum = 0.0;
    for (int a = 0; a < 3; ++a)
      sum += (b[a] = 0.05 + u(rng));
    for (int a = 0; a < 3; ++a)
      b[a] /= sum;
    mesh->GetCellPoints(c, ids);
    double x[3] = { 0, 0, 0 }, e[Dim] = {}, m[6] = {};
    for (int a = 0; a < 3; ++a)
    {
      double p[3];
      mesh->GetPoint(ids->GetId(a), p);
      for (int d = 0; d < 3; ++d)
        x[d] += b[a] * p[d];
      for (int d = 0; d < Dim; ++d)
        e[d] += b[a] * mesh->GetPointData()->GetArray("Embedding")->GetComponent(ids->GetId(a), d);
      for (int d = 0; d < 6; ++d)
        m[d] += b[a] * mesh->GetPointData()->GetArray("Metric")->GetComponent(ids->GetId(a), d);
    }
    points->InsertNextPoint(x);
    cellIds->InsertNextValue(static_cast<int>(c));
    bary->InsertNextTuple(b);
    embedding->InsertNextTuple(e);
    metric->InsertNextTuple(m);
  }
  sites->SetPoints(points);
  sites->GetPointData()->AddArray(cellIds);
  sites->GetPointData()->AddArray(bary);
  sites->GetPointData()->AddArray(embedding);
  sites->GetPointData()->AddArray(metric);
  return sites;
}

int NegativeTriangles(vtkUnstructuredGrid* out)
{
  int neg = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    double p[3][3];
    for (int a = 0; a < 3; ++a)
      out->GetPoint(ids->GetId(a), p[a]);
    const double area2 =
      (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    neg += area2 <= 0.0;
  }
  return neg;
}
// The input sites come first, unchanged, with their own point data.
void CheckInputSites(vtkUnstructuredGrid* out, vtkPolyData* sites, vtkDataArray* inserted)
{
  const char* names[4] = { "CellId", "Barycentric", "Embedding", "Metric" };
  for (vtkIdType i = 0; i < Sites; ++i)
  {
    AV_CHECK(inserted->GetTuple1(i) == 0);
    double p[3], q[3];
    out->GetPoint(i, p);
    sites->GetPoint(i, q);
    AV_CHECK(p[0] == q[0] && p[1] == q[1] && p[2] == q[2]);
    for (const char* name : names)
    {
      vtkDataArray* a = out->GetPointData()->GetArray(name);
      vtkDataArray* b = sites->GetPointData()->GetArray(name);
      for (int c = 0; a && c < b->GetNumberOfComponents(); ++c)
        AV_CHECK(a->GetComponent(i, c) == b->GetComponent(i, c));
    }
  }
}

// Inserted site i lies in its cell at its barycentric coordinates, and its "Embedding" and
// "Metric" are interpolated from the mesh there.
void CheckInsertedSite(vtkUnstructuredGrid* out, vtkUnstructuredGrid* mesh, vtkIdType i)
{
  vtkDataArray* cellId = out->GetPointData()->GetArray("CellId");
  vtkDataArray* bary = out->GetPointData()->GetArray("Barycentric");
  vtkDataArray* outEmbedding = out->GetPointData()->GetArray("Embedding");
  vtkDataArray* outMetric = out->GetPointData()->GetArray("Metric");
  vtkDataArray* meshEmbedding = mesh->GetPointData()->GetArray("Embedding");
  vtkDataArray* meshMetric = mesh->GetPointData()->GetArray("Metric");
  const vtkIdType c = static_cast<vtkIdType>(cellId->GetTuple1(i));
  AV_CHECK(c >= 0 && c < mesh->GetNumberOfCells());
  if (c < 0 || c >= mesh->GetNumberOfCells())
    return;
  vtkNew<vtkIdList> ids;
  mesh->GetCellPoints(c, ids);
  double b[4], sum = 0.0;
  for (int a = 0; a < 4; ++a)
  {
    b[a] = bary->GetComponent(i, a);
    AV_CHECK(b[a] >= 0.0);
    sum += b[a];
  }
  AV_CHECK_NEAR(sum, 1.0, 1e-12);
  AV_CHECK(b[3] == 0.0);
  double p[3], x[3] = { 0, 0, 0 };
  out->GetPoint(i, p);
  for (int a = 0; a < 3; ++a)
  {
    double v[3];
    mesh->GetPoint(ids->GetId(a), v);
    for (int d = 0; d < 3; ++d)
      x[d] += b[a] * v[d];
  }
  for (int d = 0; d < 3; ++d)
    AV_CHECK_NEAR(p[d], x[d], 1e-12);
  for (int d = 0; d < Dim; ++d)
  {
    double e = 0.0;
    for (int a = 0; a < 3; ++a)
      e += b[a] * meshEmbedding->GetComponent(ids->GetId(a), d);
    AV_CHECK_NEAR(outEmbedding->GetComponent(i, d), e, 1e-12);
  }
  for (int d = 0; d < 6; ++d)
  {
    double m = 0.0;
    for (int a = 0; a < 3; ++a)
      m += b[a] * meshMetric->GetComponent(ids->GetId(a), d);
    AV_CHECK_NEAR(outMetric->GetComponent(i, d), m, 1e-12);
  }
}

// Without repair: inverted triangles are reported (the case exercises the repair); returns
// their number.
double CheckWithoutRepair(vtkAnisoRestrictedDelaunay* rdt, EventCounter* events)
{
  rdt->RepairInvertedOff();
  rdt->Update();
  vtkUnstructuredGrid* out = rdt->GetOutput();
  const double before = FieldValue(out, "NumInverted");
  std::printf("no repair: %lld triangles, %g inverted, %d negative\n",
    static_cast<long long>(out->GetNumberOfCells()), before, NegativeTriangles(out));
  AV_CHECK(before > 0);
  AV_CHECK(NegativeTriangles(out) == static_cast<int>(before));
  AV_CHECK(out->GetNumberOfPoints() == Sites);
  AV_CHECK(FieldValue(out, "NumInsertedSites") == 0 && FieldValue(out, "RepairRounds") == 0);
  AV_CHECK(events->Warnings == 1); // what remains is reported
  AV_CHECK(events->Errors == 0);
  return before;
}

// With repair: no inverted triangle is left; the input sites are kept, the inserted ones
// have consistent point data.
void CheckWithRepair(vtkAnisoRestrictedDelaunay* rdt, EventCounter* events,
  vtkUnstructuredGrid* mesh, vtkPolyData* sites, double before)
{
  events->Reset();
  rdt->RepairInvertedOn();
  rdt->Update();
  vtkUnstructuredGrid* out = rdt->GetOutput();
  const vtkIdType n = out->GetNumberOfPoints();
  std::printf("repair: %lld triangles, %lld points, inserted %g in %g round(s), inverted %g\n",
    static_cast<long long>(out->GetNumberOfCells()), static_cast<long long>(n),
    FieldValue(out, "NumInsertedSites"), FieldValue(out, "RepairRounds"),
    FieldValue(out, "NumInverted"));
  AV_CHECK(events->Errors == 0);
  AV_CHECK(FieldValue(out, "NumInverted") == 0);
  AV_CHECK(NegativeTriangles(out) == 0);
  AV_CHECK(FieldValue(out, "NumInvertedBeforeRepair") == before);
  AV_CHECK(FieldValue(out, "NumInsertedSites") == static_cast<double>(n - Sites));
  AV_CHECK(rdt->GetNumberOfInsertedSites() == n - Sites && n > Sites);
  AV_CHECK(FieldValue(out, "RepairRounds") >= 1 && rdt->GetNumberOfRepairRounds() >= 1);
  vtkDataArray* inserted = out->GetPointData()->GetArray("InsertedSite");
  vtkDataArray* inverted = out->GetCellData()->GetArray("Inverted");
  AV_CHECK(inserted && inverted);
  if (!inserted || !inverted)
    return;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
    AV_CHECK(inverted->GetTuple1(c) == 0);
  CheckInputSites(out, sites, inserted);
  vtkDataArray* cellId = out->GetPointData()->GetArray("CellId");
  vtkDataArray* bary = out->GetPointData()->GetArray("Barycentric");
  vtkDataArray* outEmbedding = out->GetPointData()->GetArray("Embedding");
  vtkDataArray* outMetric = out->GetPointData()->GetArray("Metric");
  AV_CHECK(cellId && bary && outEmbedding && outMetric);
  if (!cellId || !bary || !outEmbedding || !outMetric)
    return;
  for (vtkIdType i = Sites; i < n; ++i)
  {
    AV_CHECK(inserted->GetTuple1(i) == 1);
    CheckInsertedSite(out, mesh, i);
  }
}
} // namespace

int TestAnisoDelaunayRepair(int, char*[])
{
  vtkNew<vtkUnstructuredGrid> mesh = MakeMesh();
  vtkNew<vtkPolyData> sites = MakeSites(mesh);
  vtkNew<vtkAnisoRestrictedDelaunay> rdt;
  vtkNew<EventCounter> events;
  av_vtk_test::Watch(rdt, events);
  rdt->SetInputData(0, mesh);
  rdt->SetInputData(1, sites);
  AV_CHECK(rdt->GetRepairInverted() && rdt->GetMaxRepairRounds() == 10 &&
    rdt->GetRepairNonManifold());
  // The input sites must stay as given (checked below): no ODT / sliver improvement rounds.
  AV_CHECK(rdt->GetImprovementRounds() == 1);
  rdt->SetImprovementRounds(0);
  // Nor the final mesh improvement (it moves sites too); checked at the end.
  AV_CHECK(rdt->GetImproveMesh());
  rdt->ImproveMeshOff();

  const double before = CheckWithoutRepair(rdt, events);
  CheckWithRepair(rdt, events, mesh, sites, before);

  // No rounds allowed: same as no repair.
  rdt->SetMaxRepairRounds(0);
  rdt->Update();
  AV_CHECK(rdt->GetOutput()->GetNumberOfPoints() == Sites);
  AV_CHECK(FieldValue(rdt->GetOutput(), "NumInverted") == before);

  // Repair and mesh improvement (the defaults): still valid, and the improvement worked
  // (the mesh carries "Metric"), with moved sites' point data interpolated where they are.
  rdt->SetMaxRepairRounds(10);
  rdt->ImproveMeshOn();
  events->Reset();
  rdt->Update();
  vtkUnstructuredGrid* out = rdt->GetOutput();
  std::printf("repair + improvement: %g flips, %g moves, inverted %g\n",
    FieldValue(out, "NumImprovementFlips"), FieldValue(out, "NumImprovementMoves"),
    FieldValue(out, "NumInverted"));
  AV_CHECK(events->Errors == 0);
  AV_CHECK(FieldValue(out, "NumInverted") == 0 && NegativeTriangles(out) == 0);
  AV_CHECK(FieldValue(out, "NumImprovementFlips") + FieldValue(out, "NumImprovementMoves") > 0);
  vtkDataArray* emb = out->GetPointData()->GetArray("Embedding");
  AV_CHECK(emb != nullptr);
  for (vtkIdType i = 0; emb && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    AV_CHECK(std::abs(emb->GetComponent(i, 0) - p[0]) < 1e-9 &&
      std::abs(emb->GetComponent(i, 1) - p[1]) < 1e-9);
  }
  // Without a metric array: a warning, the repaired dual as it is.
  rdt->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "NoSuchArray");
  events->Reset();
  rdt->Update();
  AV_CHECK(events->Warnings >= 1 && events->Errors == 0);
  AV_CHECK(FieldValue(rdt->GetOutput(), "NumImprovementMoves") == 0);
  return AV_TEST_RESULT();
}
