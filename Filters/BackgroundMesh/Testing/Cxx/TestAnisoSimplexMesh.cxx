// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkAnisoSimplexMesh on a sheared block of hexahedra with one quadratic hexahedron:
// all output cells are positive tetrahedra, the volume is kept, linear point fields are
// interpolated exactly at the added points, cell data follows the parent, the mesh is
// conforming (interior faces shared by exactly two tets), simplicial input passes through
// unchanged, a quad mesh becomes triangles of the same area, unsupported types are named.
#include "vtkAnisoSimplexMesh.h"
#include "vtkAnisoTestUtilities.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace
{
using av_vtk_test::EventCounter;
using av_vtk_test::Watch;

// The shear x' = A x (planar faces stay planar, so the volume is det(A) x the box volume).
const double A[3][3] = { { 1.0, 0.3, 0.1 }, { 0.0, 1.2, -0.2 }, { 0.1, 0.0, 0.9 } };

double DetA()
{
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
    A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
    A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

double Field(const double r[3]) // linear in the reference coordinates
{
  return 1.0 + 2.0 * r[0] - 3.0 * r[1] + 0.5 * r[2];
}

/// nx x ny x nz hexahedra of the reference box [0,nx]x[0,ny]x[0,nz], sheared by A; cell
/// `quadratic` is a VTK_QUADRATIC_HEXAHEDRON with its 12 mid-edge nodes appended. Point data:
/// "Ref" (reference coordinates), "F" (linear field), "Id" (int); cell data "Material".
vtkSmartPointer<vtkUnstructuredGrid> MakeBlock(int nx, int ny, int nz, vtkIdType quadratic)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> ref, field;
  ref->SetName("Ref");
  ref->SetNumberOfComponents(3);
  field->SetName("F");
  vtkNew<vtkIntArray> ids;
  ids->SetName("Id");
  auto addPoint = [&](const double r[3])
  {
    double x[3];
    for (int i = 0; i < 3; ++i)
      x[i] = A[i][0] * r[0] + A[i][1] * r[1] + A[i][2] * r[2];
    const vtkIdType id = points->InsertNextPoint(x);
    ref->InsertNextTuple(r);
    field->InsertNextValue(Field(r));
    ids->InsertNextValue(static_cast<int>(id));
    return id;
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        const double r[3] = { double(i), double(j), double(k) };
        addPoint(r);
      }
  auto pid = [&](int i, int j, int k) { return vtkIdType(i + (nx + 1) * (j + (ny + 1) * k)); };
  vtkNew<vtkIntArray> material;
  material->SetName("Material");
  grid->SetPoints(points);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
      {
        vtkIdType hex[20] = { pid(i, j, k),
          pid(i + 1, j, k),
          pid(i + 1, j + 1, k),
          pid(i, j + 1, k),
          pid(i, j, k + 1),
          pid(i + 1, j, k + 1),
          pid(i + 1, j + 1, k + 1),
          pid(i, j + 1, k + 1) };
        const vtkIdType c = grid->GetNumberOfCells();
        if (c == quadratic)
        {
          // VTK edge order: 0-1, 1-2, 2-3, 3-0, 4-5, 5-6, 6-7, 7-4, 0-4, 1-5, 2-6, 3-7.
          const int edges[12][2] = { { 0, 1 },
            { 1, 2 },
            { 2, 3 },
            { 3, 0 },
            { 4, 5 },
            { 5, 6 },
            { 6, 7 },
            { 7, 4 },
            { 0, 4 },
            { 1, 5 },
            { 2, 6 },
            { 3, 7 } };
          for (int e = 0; e < 12; ++e)
          {
            double r[3];
            for (int d = 0; d < 3; ++d)
              r[d] = 0.5 *
                (ref->GetComponent(hex[edges[e][0]], d) + ref->GetComponent(hex[edges[e][1]], d));
            hex[8 + e] = addPoint(r);
          }
          grid->InsertNextCell(VTK_QUADRATIC_HEXAHEDRON, 20, hex);
        }
        else
        {
          grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
        }
        material->InsertNextValue(static_cast<int>(10 * c + 7));
      }
  grid->GetPointData()->AddArray(ref);
  grid->GetPointData()->AddArray(field);
  grid->GetPointData()->AddArray(ids);
  grid->GetCellData()->AddArray(material);
  return grid;
}

double TetVolume(vtkUnstructuredGrid* g, vtkIdType c)
{
  vtkNew<vtkIdList> ids;
  g->GetCellPoints(c, ids);
  double p[4][3];
  for (int k = 0; k < 4; ++k)
    g->GetPoint(ids->GetId(k), p[k]);
  double a[3], b[3], d[3];
  for (int i = 0; i < 3; ++i)
  {
    a[i] = p[1][i] - p[0][i];
    b[i] = p[2][i] - p[0][i];
    d[i] = p[3][i] - p[0][i];
  }
  return (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
           a[2] * (b[0] * d[1] - b[1] * d[0])) /
    6.0;
}

// All positive tets; total volume = det(A) x box volume.
void CheckPositiveVolume(vtkUnstructuredGrid* out, int nx, int ny, int nz)
{
  double volume = 0;
  bool allTets = true, allPositive = true;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    allTets = allTets && out->GetCellType(c) == VTK_TETRA;
    const double v = TetVolume(out, c);
    allPositive = allPositive && v > 1e-12;
    volume += v;
  }
  AV_CHECK(allTets);
  AV_CHECK(allPositive);
  AV_CHECK_NEAR(volume, DetA() * nx * ny * nz, 1e-12);
}

// Point data: linear fields exact at every point (added centers included); "Ref" maps back.
void CheckPointData(vtkUnstructuredGrid* out, vtkUnstructuredGrid* block, vtkIdType numHex)
{
  vtkDataArray* ref = out->GetPointData()->GetArray("Ref");
  vtkDataArray* field = out->GetPointData()->GetArray("F");
  vtkDataArray* ids = out->GetPointData()->GetArray("Id");
  AV_CHECK(ref && field && ids);
  double maxErr = 0;
  int centers = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double r[3], x[3];
    ref->GetTuple(i, r);
    out->GetPoint(i, x);
    for (int d = 0; d < 3; ++d)
      maxErr =
        std::max(maxErr, std::abs(x[d] - (A[d][0] * r[0] + A[d][1] * r[1] + A[d][2] * r[2])));
    maxErr = std::max(maxErr, std::abs(field->GetTuple1(i) - Field(r)));
    const bool isCenter = std::abs(r[0] - std::floor(r[0]) - 0.5) < 1e-12;
    centers += isCenter;
    if (!isCenter) // a kept input point keeps its "Id" and coordinates
    {
      const vtkIdType id = static_cast<vtkIdType>(ids->GetTuple1(i));
      double y[3];
      block->GetPoint(id, y);
      maxErr =
        std::max(maxErr, std::abs(x[0] - y[0]) + std::abs(x[1] - y[1]) + std::abs(x[2] - y[2]));
    }
  }
  AV_CHECK(maxErr < 1e-12);
  AV_CHECK(centers == numHex);
}

// Cell data from the parent cell.
void CheckParentCellData(vtkUnstructuredGrid* out, vtkIdType inCells, vtkIdType quadratic)
{
  auto* parent = vtkIdTypeArray::SafeDownCast(out->GetCellData()->GetArray("ParentCellId"));
  vtkDataArray* material = out->GetCellData()->GetArray("Material");
  AV_CHECK(parent && material);
  std::map<vtkIdType, int> pieces;
  bool materialOk = true;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    const vtkIdType p = parent->GetValue(c);
    ++pieces[p];
    materialOk = materialOk && material->GetTuple1(c) == 10 * p + 7;
  }
  AV_CHECK(materialOk);
  AV_CHECK(static_cast<vtkIdType>(pieces.size()) == inCells);
  AV_CHECK(pieces[quadratic] == 12);
}

// Conforming: every face is used by two tets, or by one on the box boundary.
void CheckConforming(vtkUnstructuredGrid* out, int nx, int ny, int nz)
{
  vtkDataArray* ref = out->GetPointData()->GetArray("Ref");
  std::map<std::array<vtkIdType, 3>, int> faces;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, cell);
    const int f[4][3] = { { 0, 1, 2 }, { 0, 1, 3 }, { 0, 2, 3 }, { 1, 2, 3 } };
    for (const auto& face : f)
    {
      std::array<vtkIdType, 3> key = {
        cell->GetId(face[0]), cell->GetId(face[1]), cell->GetId(face[2])
      };
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  }
  int bad = 0, boundary = 0;
  const double hi[3] = { double(nx), double(ny), double(nz) };
  for (const auto& kv : faces)
  {
    if (kv.second == 2)
      continue;
    bool onBoundary = false;
    for (int d = 0; d < 3 && !onBoundary; ++d)
      for (double side : { 0.0, hi[d] })
      {
        bool all = true;
        for (vtkIdType p : kv.first)
          all = all && std::abs(ref->GetComponent(p, d) - side) < 1e-12;
        onBoundary = onBoundary || all;
      }
    if (kv.second == 1 && onBoundary)
      ++boundary;
    else
      ++bad;
  }
  AV_CHECK(bad == 0);
  AV_CHECK(boundary == 2 * 2 * (nx * ny + ny * nz + nx * nz)); // 2 triangles per boundary square
}

// Simplicial input passes through unchanged, without a warning.
void CheckSimplicialPassThrough(vtkUnstructuredGrid* out, EventCounter* events)
{
  vtkNew<vtkUnstructuredGrid> tets;
  tets->DeepCopy(out);
  vtkNew<vtkAnisoSimplexMesh> again;
  again->AddObserver(vtkCommand::WarningEvent, events);
  again->AddObserver(vtkCommand::ErrorEvent, events);
  events->Reset();
  again->SetInputData(tets);
  AV_CHECK(again->GetExecutive()->Update() == 1);
  AV_CHECK(events->Warnings == 0 && events->Errors == 0);
  vtkUnstructuredGrid* same = again->GetOutput();
  AV_CHECK(same->GetNumberOfPoints() == tets->GetNumberOfPoints());
  AV_CHECK(same->GetNumberOfCells() == tets->GetNumberOfCells());
  bool identical = true;
  vtkNew<vtkIdList> a, b;
  for (vtkIdType c = 0; c < tets->GetNumberOfCells(); ++c)
  {
    tets->GetCellPoints(c, a);
    same->GetCellPoints(c, b);
    for (int k = 0; k < 4; ++k)
      identical = identical && a->GetId(k) == b->GetId(k);
  }
  for (vtkIdType i = 0; i < tets->GetNumberOfPoints(); ++i)
    for (int d = 0; d < 3; ++d)
      identical = identical && tets->GetPoint(i)[d] == same->GetPoint(i)[d];
  AV_CHECK(identical);
  AV_CHECK(std::string(again->GetSplitSummary()).find("nothing split") == 0);
  auto* parentAgain = vtkIdTypeArray::SafeDownCast(same->GetCellData()->GetArray("ParentCellId"));
  AV_CHECK(parentAgain && parentAgain->GetValue(17) == 17);
}

void TestHexBlock(EventCounter* events)
{
  const int nx = 3, ny = 2, nz = 2;
  const vtkIdType quadratic = 5;
  auto block = MakeBlock(nx, ny, nz, quadratic);
  const vtkIdType inPoints = block->GetNumberOfPoints();
  const vtkIdType inCells = block->GetNumberOfCells();

  vtkNew<vtkAnisoSimplexMesh> filter;
  Watch(filter, events);
  events->Reset();
  filter->SetInputData(block);
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  AV_CHECK(events->Errors == 0);
  AV_CHECK(events->Warnings == 1); // the split summary
  AV_CHECK(events->Last.find("quadratic hexahedra") != std::string::npos);
  vtkUnstructuredGrid* out = filter->GetOutput();
  const vtkIdType numHex = nx * ny * nz;
  AV_CHECK(out->GetNumberOfCells() == 12 * numHex);
  AV_CHECK(filter->GetNumberOfSplitCells() == numHex);
  AV_CHECK(filter->GetNumberOfAddedPoints() == numHex);
  // Corners + centers; the 12 mid-edge nodes of the quadratic cell are dropped.
  AV_CHECK(out->GetNumberOfPoints() == inPoints - 12 + numHex);
  auto* summary =
    vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("SplitSummary"));
  AV_CHECK(summary && summary->GetNumberOfValues() == 1 &&
    summary->GetValue(0).find("split 11 hexahedra, 1 quadratic hexahedra into 144 tetrahedra") !=
      std::string::npos);

  CheckPositiveVolume(out, nx, ny, nz);
  CheckPointData(out, block, numHex);
  CheckParentCellData(out, inCells, quadratic);
  CheckConforming(out, nx, ny, nz);
  // The input is unmodified.
  AV_CHECK(block->GetNumberOfPoints() == inPoints && block->GetNumberOfCells() == inCells);
  AV_CHECK(block->GetCellData()->GetNumberOfArrays() == 1);
  AV_CHECK(block->GetFieldData()->GetNumberOfArrays() == 0);

  CheckSimplicialPassThrough(out, events);
}

// Quads -> triangles of the same total area; a hexagonal prism is named in the error.
void TestQuadsAndErrors(EventCounter* events)
{
  vtkNew<vtkUnstructuredGrid> quads;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      points->InsertNextPoint(i + 0.2 * j, 0.5 * j, 0.0);
  quads->SetPoints(points);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i)
    {
      const vtkIdType q[4] = { i + 4 * j, i + 1 + 4 * j, i + 1 + 4 * (j + 1), i + 4 * (j + 1) };
      quads->InsertNextCell(VTK_QUAD, 4, q);
    }
  vtkNew<vtkAnisoSimplexMesh> filter;
  Watch(filter, events);
  filter->SetInputData(quads);
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 1);
  vtkUnstructuredGrid* out = filter->GetOutput();
  AV_CHECK(out->GetNumberOfCells() == 12);
  AV_CHECK(out->GetNumberOfPoints() == 12);
  double area = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    AV_CHECK(out->GetCellType(c) == VTK_TRIANGLE);
    out->GetCellPoints(c, ids);
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      out->GetPoint(ids->GetId(k), p[k]);
    area += 0.5 *
      std::abs(
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
  }
  AV_CHECK_NEAR(area, 3.0 * 1.0, 1e-12); // 3 x 2 parallelograms of base 1 and height 0.5

  vtkNew<vtkUnstructuredGrid> prism;
  vtkNew<vtkPoints> pp;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 6; ++i)
      pp->InsertNextPoint(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), double(k));
  prism->SetPoints(pp);
  vtkIdType hp[12];
  for (int i = 0; i < 12; ++i)
    hp[i] = i;
  prism->InsertNextCell(VTK_HEXAGONAL_PRISM, 12, hp);
  filter->SetInputData(prism);
  events->Reset();
  AV_CHECK(filter->GetExecutive()->Update() == 0);
  AV_CHECK(events->Errors >= 1);
  AV_CHECK(events->All.find("VTK_HEXAGONAL_PRISM") != std::string::npos);
}
}

int TestAnisoSimplexMesh(int, char*[])
{
  vtkNew<EventCounter> events;
  TestHexBlock(events);
  TestQuadsAndErrors(events);
  return AV_TEST_RESULT();
}
