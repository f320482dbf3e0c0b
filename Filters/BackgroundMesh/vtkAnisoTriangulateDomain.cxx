// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoTriangulateDomain.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDelaunay2D.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolygon.h>

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkAnisoTriangulateDomain);

namespace
{
struct Loop
{
  std::vector<double> XY; // closed loop, last point != first
};

double SegmentDistance(const double p[2], const double a[2], const double b[2])
{
  const double ab[2] = { b[0] - a[0], b[1] - a[1] };
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1];
  double t = len2 > 0 ? ((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / len2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  const double dx = a[0] + t * ab[0] - p[0], dy = a[1] + t * ab[1] - p[1];
  return std::sqrt(dx * dx + dy * dy);
}
/// Boundary loops of the domain: the input's polygons, else its closed polylines, else the
/// bounding rectangle `b`.
std::vector<Loop> CollectLoops(vtkPolyData* input, const double b[6])
{
  std::vector<Loop> loops;
  auto addCells = [&](vtkCellArray* cells, bool needClosed)
  {
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdList* ids = it->GetCurrentCell();
      vtkIdType n = ids->GetNumberOfIds();
      if (needClosed)
      {
        if (n < 4 || ids->GetId(0) != ids->GetId(n - 1))
          continue;
        --n;
      }
      if (n < 3)
        continue;
      Loop loop;
      for (vtkIdType k = 0; k < n; ++k)
      {
        double p[3];
        input->GetPoint(ids->GetId(k), p);
        loop.XY.push_back(p[0]);
        loop.XY.push_back(p[1]);
      }
      loops.push_back(loop);
    }
  };
  addCells(input->GetPolys(), false);
  if (loops.empty())
    addCells(input->GetLines(), true);
  if (loops.empty())
  {
    loops.push_back(Loop{ { b[0], b[2], b[1], b[2], b[1], b[3], b[0], b[3] } });
  }

  return loops;
}

/// vtkDelaunay2D keeps what is left of a counter-clockwise loop: outer loops (inside an even
/// number of other loops) must be counter-clockwise, holes clockwise.
void OrientLoops(std::vector<Loop>& loops)
{
  for (std::size_t l = 0; l < loops.size(); ++l)
  {
    std::vector<double>& xy = loops[l].XY;
    const std::size_t n = xy.size() / 2;
    double area2 = 0;
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::size_t j = (k + 1) % n;
      area2 += xy[2 * k] * xy[2 * j + 1] - xy[2 * j] * xy[2 * k + 1];
    }
    int depth = 0;
    for (std::size_t o = 0; o < loops.size(); ++o)
    {
      if (o == l)
        continue;
      const std::vector<double>& q = loops[o].XY;
      const std::size_t m = q.size() / 2;
      bool in = false;
      for (std::size_t k = 0, j = m - 1; k < m; j = k++)
      {
        if (((q[2 * k + 1] > xy[1]) != (q[2 * j + 1] > xy[1])) &&
          (xy[0] < (q[2 * j] - q[2 * k]) * (xy[1] - q[2 * k + 1]) / (q[2 * j + 1] - q[2 * k + 1]) +
              q[2 * k]))
          in = !in;
      }
      depth += in ? 1 : 0;
    }
    if ((depth % 2 == 0) != (area2 > 0))
    {
      for (std::size_t k = 0; k < n / 2; ++k)
      {
        std::swap(xy[2 * k], xy[2 * (n - 1 - k)]);
        std::swap(xy[2 * k + 1], xy[2 * (n - 1 - k) + 1]);
      }
    }
  }
}

/// The boundary resampled at spacing <= h: its points go into `points`, one polygon per loop
/// into `boundaryPolys` and `polygons` (for the inside tests).
void ResampleBoundary(const std::vector<Loop>& loops,
  double h,
  vtkPoints* points,
  vtkCellArray* boundaryPolys,
  std::vector<vtkSmartPointer<vtkPolygon>>& polygons)
{
  for (const Loop& loop : loops)
  {
    const std::size_t n = loop.XY.size() / 2;
    std::vector<vtkIdType> ids;
    vtkNew<vtkPolygon> polygon;
    polygon->GetPoints()->SetDataTypeToDouble();
    for (std::size_t k = 0; k < n; ++k)
    {
      const double* a = &loop.XY[2 * k];
      const double* c = &loop.XY[2 * ((k + 1) % n)];
      const double len = std::hypot(c[0] - a[0], c[1] - a[1]);
      const int pieces = std::max(1, static_cast<int>(std::ceil(len / h - 1e-9)));
      for (int s = 0; s < pieces; ++s)
      {
        const double t = static_cast<double>(s) / pieces;
        const double x = a[0] + t * (c[0] - a[0]), y = a[1] + t * (c[1] - a[1]);
        ids.push_back(points->InsertNextPoint(x, y, 0.0));
        polygon->GetPoints()->InsertNextPoint(x, y, 0.0);
      }
    }
    polygon->GetPointIds()->SetNumberOfIds(polygon->GetPoints()->GetNumberOfPoints());
    for (vtkIdType k = 0; k < polygon->GetPoints()->GetNumberOfPoints(); ++k)
      polygon->GetPointIds()->SetId(k, k);
    boundaryPolys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    polygons.push_back(polygon);
  }
}

/// Interior points on an equilateral lattice of spacing h, kept inside an odd number of loops
/// and away from the boundary (so that no sliver triangles appear next to it).
void AddInteriorLattice(const double b[6],
  double h,
  const std::vector<vtkSmartPointer<vtkPolygon>>& polygons,
  vtkPoints* points)
{
  const double rowH = h * std::sqrt(3.0) / 2.0;
  int row = 0;
  for (double y = b[2] + rowH * 0.5; y < b[3]; y += rowH, ++row)
  {
    for (double x = b[0] + (row % 2 ? h * 0.5 : 0.0); x < b[1]; x += h)
    {
      const double p[3] = { x, y, 0.0 };
      int inside = 0;
      double dmin = VTK_DOUBLE_MAX;
      for (std::size_t l = 0; l < polygons.size(); ++l)
      {
        vtkPolygon* poly = polygons[l];
        double pb[6];
        poly->GetPoints()->GetBounds(pb);
        double n[3] = { 0, 0, 1 };
        auto* pts = static_cast<double*>(poly->GetPoints()->GetVoidPointer(0));
        if (vtkPolygon::PointInPolygon(
              const_cast<double*>(p), poly->GetPoints()->GetNumberOfPoints(), pts, pb, n) == 1)
          ++inside;
        const vtkIdType np = poly->GetPoints()->GetNumberOfPoints();
        for (vtkIdType k = 0; k < np; ++k)
        {
          const double* a = pts + 3 * k;
          const double* c = pts + 3 * ((k + 1) % np);
          dmin = std::min(dmin, SegmentDistance(p, a, c));
        }
      }
      if (inside % 2 == 1 && dmin > 0.5 * h)
        points->InsertNextPoint(p);
    }
  }
}

/// The counter-clockwise triangles of `tri` (clockwise ones reoriented, flat ones dropped).
vtkSmartPointer<vtkCellArray> CounterClockwiseTriangles(vtkPolyData* tri, double h)
{
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  auto it = vtk::TakeSmartPointer(tri->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdList* ids = it->GetCurrentCell();
    if (ids->GetNumberOfIds() != 3)
      continue;
    vtkIdType t[3] = { ids->GetId(0), ids->GetId(1), ids->GetId(2) };
    double p0[3], p1[3], p2[3];
    tri->GetPoint(t[0], p0);
    tri->GetPoint(t[1], p1);
    tri->GetPoint(t[2], p2);
    const double area2 = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]);
    if (std::abs(area2) <= 1e-14 * h * h)
      continue;
    if (area2 < 0)
      std::swap(t[1], t[2]);
    triangles->InsertNextCell(3, t);
  }
  return triangles;
}
}

vtkAnisoTriangulateDomain::vtkAnisoTriangulateDomain() = default;

int vtkAnisoTriangulateDomain::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }
  double b[6];
  input->GetBounds(b);
  if (b[4] != b[5])
  {
    vtkErrorMacro("the domain must lie in a plane z = constant; its z range is [" << b[4] << ", "
                                                                                  << b[5] << "]");
    return 0;
  }
  const double dx = b[1] - b[0], dy = b[3] - b[2];
  if (!(dx > 0) || !(dy > 0) || !std::isfinite(dx) || !std::isfinite(dy))
  {
    vtkErrorMacro("the domain has zero area or non-finite bounds");
    return 0;
  }
  double h = this->TargetEdgeLength > 0 ? this->TargetEdgeLength : std::hypot(dx, dy) / 50.0;
  if (std::max(dx, dy) / h > 4000)
  {
    vtkErrorMacro("TargetEdgeLength " << h << " would give more than ~10^7 triangles");
    return 0;
  }

  std::vector<Loop> loops = CollectLoops(input, b);
  OrientLoops(loops);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> boundaryPolys;
  std::vector<vtkSmartPointer<vtkPolygon>> polygons;
  ResampleBoundary(loops, h, points, boundaryPolys, polygons);
  AddInteriorLattice(b, h, polygons, points);

  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkPolyData> boundary;
  boundary->SetPoints(points);
  boundary->SetPolys(boundaryPolys);
  vtkNew<vtkDelaunay2D> delaunay;
  delaunay->SetInputData(cloud);
  delaunay->SetSourceData(boundary);
  delaunay->SetTolerance(1e-9);
  delaunay->Update();
  vtkPolyData* tri = delaunay->GetOutput();
  if (tri->GetNumberOfPolys() == 0)
  {
    vtkErrorMacro("the triangulation of the domain is empty (is the boundary a valid, "
                  "non-self-intersecting polygon?)");
    return 0;
  }
  vtkSmartPointer<vtkCellArray> triangles = CounterClockwiseTriangles(tri, h);
  output->SetPoints(tri->GetPoints());
  output->SetPolys(triangles);
  return 1;
}

void vtkAnisoTriangulateDomain::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetEdgeLength: " << this->TargetEdgeLength << "\n";
}
