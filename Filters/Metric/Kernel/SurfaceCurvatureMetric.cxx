// SPDX-License-Identifier: BSD-3-Clause
#include "SurfaceCurvatureMetric.h"

#include "MeshTopology.h"
#include "MetricAlgebra.h"
#include "VertexGraph.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace av
{
namespace
{
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// Some unit vector orthogonal to the unit vector n.
Vec3 AnyTangent(const Vec3& n)
{
  const Vec3 a = std::abs(n[0]) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (a - a.dot(n) * n).normalized();
}

/// Checks the surface and the options; returns the bounding-box diagonal.
double ValidateSurface(const SimplexMesh& s, const SurfaceCurvatureMetricOptions& opt)
{
  const std::string who = "SurfaceCurvatureMetric: ";
  if (s.AmbientDim != 3 || s.SimplexDim != 2)
  {
    throw InputError(who + "expected a triangle surface in 3D (AmbientDim 3, SimplexDim 2)");
  }
  if (s.Points.size() % 3 != 0 || s.Cells.size() % 3 != 0 || s.NumCells() == 0)
  {
    throw InputError(who + "the surface is empty or its arrays have inconsistent sizes");
  }
  if (!(opt.CurvatureThreshold > 0.0) || !std::isfinite(opt.CurvatureThreshold))
  {
    throw InputError(who + "CurvatureThreshold must be positive");
  }
  if (opt.SmoothingIterations < 0 || !(opt.MaxStretch == 0.0 || opt.MaxStretch >= 1.0))
  {
    throw InputError(who + "SmoothingIterations must be >= 0 and MaxStretch 0 or >= 1");
  }
  if (!(opt.CreaseAngle > 0.0 && opt.CreaseAngle <= 180.0))
  {
    throw InputError(who + "CreaseAngle must be in (0, 180] degrees");
  }
  const std::size_t np = s.NumPoints();
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  for (std::size_t i = 0; i < np; ++i)
  {
    const Eigen::Map<const Vec3> p(s.Point(i));
    if (!p.allFinite())
    {
      throw InputError(who + "point " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

/// Vertex normals with Max's weights (InputError on bad ids, zero-area or unused triangles).
/// Max's (1999) weighted normal term at corner k of the triangle x: (e1 x e2) / (|e1|^2 |e2|^2),
/// n2 = (x1 - x0) x (x2 - x0).
Vec3 MaxCornerTerm(const Vec3 (&x)[3], int k, const Vec3& n2)
{
  const Vec3 e1 = x[(k + 1) % 3] - x[k], e2 = x[(k + 2) % 3] - x[k];
  return n2 / (e1.squaredNorm() * e2.squaredNorm());
}

/// The local index (0, 1, 2) of vertex v in triangle t.
int CornerOf(const std::int32_t* t, std::size_t v)
{
  return t[0] == static_cast<std::int32_t>(v) ? 0 : t[1] == static_cast<std::int32_t>(v) ? 1 : 2;
}

std::vector<Vec3> VertexNormals(const SimplexMesh& s, double diag)
{
  const std::string who = "SurfaceCurvatureMetric: ";
  const std::size_t np = s.NumPoints(), nc = s.NumCells();
  std::vector<Vec3> normal(np, Vec3::Zero());
  CheckCellIds(s, who, "triangle");
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* t = s.Cell(c);
    const Eigen::Map<const Vec3> a(s.Point(t[0])), b(s.Point(t[1])), d(s.Point(t[2]));
    const Vec3 n2 = (b - a).cross(d - a); // twice the area times the unit normal
    if (!(n2.norm() > 1e-14 * diag * diag))
    {
      throw InputError(who + "triangle " + std::to_string(c) + " has zero area");
    }
    // Max's (1999) weights: the face normal times sin(angle) / (|e1| |e2|) at each corner,
    // i.e. (e1 x e2) / (|e1|^2 |e2|^2). Exact on a sphere, and second order on irregular
    // one-rings where area weights leave a first-order tilt that the normal-difference
    // curvature fit below turns into a curvature error.
    const Vec3 x[3] = { a, b, d };
    for (int k = 0; k < 3; ++k)
      normal[static_cast<std::size_t>(t[k])] += MaxCornerTerm(x, k, n2);
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    const double len = normal[i].norm();
    if (!(len > 0.0))
    {
      throw InputError(who + "point " + std::to_string(i) +
        " is used by no triangle (or its triangles cancel out); remove unused points");
    }
    normal[i] /= len;
  }

  return normal;
}

/// Per face: second fundamental form in 3D (tangent to the face) from the differences of its
/// corner normals, and the face's weight (a third of its area).
void FaceShapeOperators(const SimplexMesh& s,
  const std::vector<Vec3>& cornerNormal,
  std::vector<Mat3>& faceForm,
  std::vector<double>& faceWeight)
{
  const std::size_t nc = s.NumCells();
  faceForm.resize(nc);
  faceWeight.resize(nc);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 512),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c != range.end(); ++c)
      {
        const std::int32_t* t = s.Cell(c);
        const Eigen::Map<const Vec3> x[3] = { Eigen::Map<const Vec3>(s.Point(t[0])),
          Eigen::Map<const Vec3>(s.Point(t[1])),
          Eigen::Map<const Vec3>(s.Point(t[2])) };
        const Vec3 n2 = (x[1] - x[0]).cross(x[2] - x[0]);
        const Vec3 nf = n2.normalized();
        const Vec3 tu = (x[1] - x[0]).normalized();
        const Vec3 tv = nf.cross(tu);
        Mat3 A = Mat3::Zero();
        Vec3 rhs = Vec3::Zero();
        for (int k = 0; k < 3; ++k)
        {
          const int p = (k + 1) % 3, q = (k + 2) % 3;
          const Vec3 e = x[q] - x[p];
          const Vec3 dn = cornerNormal[3 * c + static_cast<std::size_t>(q)] -
            cornerNormal[3 * c + static_cast<std::size_t>(p)];
          const double u = e.dot(tu), v = e.dot(tv);
          const Vec3 r1(u, v, 0.0), r2(0.0, u, v);
          A += r1 * r1.transpose() + r2 * r2.transpose();
          rhs += r1 * dn.dot(tu) + r2 * dn.dot(tv);
        }
        const Vec3 efg = A.ldlt().solve(rhs);
        faceForm[c] = efg[0] * tu * tu.transpose() +
          efg[1] * (tu * tv.transpose() + tv * tu.transpose()) + efg[2] * tv * tv.transpose();
        faceWeight[c] = n2.norm() / 6.0; // a third of the area
      }
    });
}

/// The triangles around each vertex (CSR: offsets, list).
void VertexFaces(const SimplexMesh& s,
  std::vector<std::int32_t>& vfOffset,
  std::vector<std::int32_t>& vfList)
{
  const std::size_t np = s.NumPoints(), nc = s.NumCells();
  vfOffset.assign(np + 1, 0);
  vfList.resize(3 * nc);
  for (std::size_t c = 0; c < nc; ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++vfOffset[static_cast<std::size_t>(s.Cell(c)[k]) + 1];
    }
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    vfOffset[i + 1] += vfOffset[i];
  }
  {
    std::vector<std::int32_t> fill(vfOffset.begin(), vfOffset.end() - 1);
    for (std::size_t c = 0; c < nc; ++c)
    {
      for (int k = 0; k < 3; ++k)
      {
        vfList[static_cast<std::size_t>(fill[s.Cell(c)[k]]++)] = static_cast<std::int32_t>(c);
      }
    }
  }
}

/// Per triangle corner (3 per cell): the unit normal of its wedge, the faces around the corner's
/// vertex that are connected through edges at the vertex which are not creases (normals more
/// than creaseAngle apart, or an edge of more than two faces). The wedge normal sums the same
/// Max-weighted terms as VertexNormals, over the wedge's faces in the same (cell) order, so a
/// vertex with no crease gets its vertex normal bit for bit. Counts the crease edges.
std::vector<Vec3> CornerNormals(const SimplexMesh& s,
  const std::vector<Vec3>& normal,
  double creaseAngle,
  const std::vector<std::int32_t>& vfOffset,
  const std::vector<std::int32_t>& vfList,
  std::size_t& numCreaseEdges)
{
  const std::size_t np = s.NumPoints(), nc = s.NumCells();
  std::vector<Vec3> corner(3 * nc);
  numCreaseEdges = 0;
  if (creaseAngle >= 180.0)
  {
    for (std::size_t c = 0; c < nc; ++c)
      for (int k = 0; k < 3; ++k)
        corner[3 * c + static_cast<std::size_t>(k)] = normal[static_cast<std::size_t>(s.Cell(c)[k])];
    return corner;
  }
  const double cosCrease = std::cos(creaseAngle * 3.14159265358979323846 / 180.0);
  // Unit face normals and the Max-weighted corner terms of VertexNormals.
  std::vector<Vec3> faceNormal(nc), term(3 * nc);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 1024),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c != range.end(); ++c)
      {
        const std::int32_t* t = s.Cell(c);
        const Vec3 x[3] = { Eigen::Map<const Vec3>(s.Point(t[0])),
          Eigen::Map<const Vec3>(s.Point(t[1])), Eigen::Map<const Vec3>(s.Point(t[2])) };
        const Vec3 n2 = (x[1] - x[0]).cross(x[2] - x[0]);
        faceNormal[c] = n2.normalized();
        for (int k = 0; k < 3; ++k)
          term[3 * c + static_cast<std::size_t>(k)] = MaxCornerTerm(x, k, n2);
      }
    });
  std::vector<std::size_t> creases(np, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 256),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      // Reused per vertex: union-find over the vertex's faces, the far vertex of each edge at
      // the vertex with its two first faces and face count, the wedge sums.
      std::vector<std::int32_t> parent;
      std::vector<std::array<std::int32_t, 4>> edges; // far vertex, first, second face, count
      std::vector<Vec3> sum;
      for (std::size_t v = range.begin(); v != range.end(); ++v)
      {
        const std::int32_t begin = vfOffset[v], deg = vfOffset[v + 1] - begin;
        parent.resize(static_cast<std::size_t>(deg));
        for (std::int32_t a = 0; a < deg; ++a)
          parent[static_cast<std::size_t>(a)] = a;
        const auto find = [&](std::int32_t a)
        {
          while (parent[static_cast<std::size_t>(a)] != a)
            a = parent[static_cast<std::size_t>(a)] =
              parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
          return a;
        };
        edges.clear();
        for (std::int32_t a = 0; a < deg; ++a)
        {
          const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + a)]);
          for (int k = 0; k < 3; ++k)
          {
            const std::int32_t x = s.Cell(f)[k];
            if (static_cast<std::size_t>(x) == v)
              continue;
            auto it = std::find_if(edges.begin(), edges.end(),
              [x](const std::array<std::int32_t, 4>& e) { return e[0] == x; });
            if (it == edges.end())
              edges.push_back({ x, a, -1, 1 });
            else if (++(*it)[3] == 2)
              (*it)[2] = a;
          }
        }
        // Join the two faces of each manifold edge unless it is sharp; an edge of three or more
        // faces separates them. Each crease is counted at its lower vertex.
        for (const auto& e : edges)
        {
          bool crease = e[3] > 2;
          if (e[3] == 2)
          {
            const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + e[1])]);
            const auto g = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + e[2])]);
            crease = !(faceNormal[f].dot(faceNormal[g]) >= cosCrease);
            if (!crease)
              parent[static_cast<std::size_t>(find(e[1]))] = find(e[2]);
          }
          if (crease && static_cast<std::size_t>(e[0]) > v)
            ++creases[v];
        }
        // A vertex with one wedge keeps its vertex normal (bit for bit).
        bool oneWedge = true;
        for (std::int32_t a = 1; a < deg && oneWedge; ++a)
          oneWedge = find(a) == find(0);
        if (oneWedge)
        {
          for (std::int32_t a = 0; a < deg; ++a)
          {
            const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + a)]);
            corner[3 * f + static_cast<std::size_t>(CornerOf(s.Cell(f), v))] = normal[v];
          }
          continue;
        }
        sum.assign(static_cast<std::size_t>(deg), Vec3::Zero());
        for (std::int32_t a = 0; a < deg; ++a)
        {
          const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + a)]);
          sum[static_cast<std::size_t>(find(a))] +=
            term[3 * f + static_cast<std::size_t>(CornerOf(s.Cell(f), v))];
        }
        for (std::int32_t a = 0; a < deg; ++a)
        {
          const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(begin + a)]);
          const Vec3& w = sum[static_cast<std::size_t>(find(a))];
          const double len = w.norm();
          corner[3 * f + static_cast<std::size_t>(CornerOf(s.Cell(f), v))] =
            len > 0.0 ? Vec3(w / len) : normal[v];
        }
      }
    });
  for (std::size_t v = 0; v < np; ++v)
    numCreaseEdges += creases[v];
  return corner;
}

/// Per vertex: principal curvatures (ordered by magnitude), the stretch pair (s1, s2) and the
/// line field confidence * v_max v_max^T that the smoothing averages.
void PrincipalCurvatures(const SimplexMesh& s,
  const std::vector<Vec3>& normal,
  const std::vector<Mat3>& faceForm,
  const std::vector<double>& faceWeight,
  const std::vector<std::int32_t>& vfOffset,
  const std::vector<std::int32_t>& vfList,
  SurfaceCurvatureMetricResult& r,
  std::vector<Eigen::Vector2d>& stretch,
  std::vector<Mat3>& lineField)
{
  const std::size_t np = s.NumPoints();
  r.MinCurvature.resize(np);
  r.MaxCurvature.resize(np);
  stretch.resize(np);   // (s1, s2)
  lineField.resize(np); // confidence * v_max v_max^T
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 512),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        Mat3 T = Mat3::Zero();
        double w = 0.0;
        for (std::int32_t k = vfOffset[i]; k < vfOffset[i + 1]; ++k)
        {
          const auto f = static_cast<std::size_t>(vfList[static_cast<std::size_t>(k)]);
          T += faceWeight[f] * faceForm[f];
          w += faceWeight[f];
        }
        T /= w;
        const Vec3& n = normal[i];
        const Vec3 t1 = AnyTangent(n), t2 = n.cross(t1);
        Eigen::Matrix2d T2;
        T2 << t1.dot(T * t1), t1.dot(T * t2), t2.dot(T * t1), t2.dot(T * t2);
        const SymmetricEigen2 e = EigenDecompose(T2);
        // Order by magnitude: v_min belongs to the curvature closer to zero.
        const int small = std::abs(e.Values[0]) <= std::abs(e.Values[1]) ? 0 : 1;
        const int large = 1 - small;
        r.MinCurvature[i] = e.Values[small];
        r.MaxCurvature[i] = e.Values[large];
        const Vec3 vmax = e.Vectors(0, large) * t1 + e.Vectors(1, large) * t2;
        const double s1 = std::sqrt(std::max(std::abs(e.Values[small]), r.CurvatureFloor));
        const double s2 = std::sqrt(std::max(std::abs(e.Values[large]), r.CurvatureFloor));
        stretch[i] = Eigen::Vector2d(s1, s2);
        // Umbilic points have arbitrary directions: let anisotropic neighbors decide.
        const double confidence = (s2 - s1) / (s2 + s1) + 1e-6;
        lineField[i] = confidence * vmax * vmax.transpose();
      }
    });
}

/// Laplacian smoothing of the stretch pairs and the line field (paper §6, after Alliez et al.).
void SmoothStretchAndDirections(const SimplexMesh& s,
  int iterations,
  std::vector<Eigen::Vector2d>& stretch,
  std::vector<Mat3>& lineField)
{
  const std::size_t np = s.NumPoints();
  const VertexGraph graph = BuildVertexGraph(np, UniqueEdges(s));
  std::vector<Eigen::Vector2d> s2(np);
  std::vector<Mat3> l2(np);
  for (int it = 0; it < iterations; ++it)
  {
    HalfLaplacianStep(graph, stretch, s2);
    stretch.swap(s2);
    HalfLaplacianStep(graph, lineField, l2);
    lineField.swap(l2);
  }
}

/// Eq. 19: M = v_min v_min^T + (s2 / s1)^2 v_max v_max^T in the tangent plane, with the
/// directions and normals of the result.
void AssembleMetric(const SimplexMesh& s,
  const SurfaceCurvatureMetricOptions& opt,
  const std::vector<Vec3>& normal,
  const std::vector<Eigen::Vector2d>& stretch,
  const std::vector<Mat3>& lineField,
  SurfaceCurvatureMetricResult& r)
{
  const std::size_t np = s.NumPoints();
  r.Metric.Values.resize(6 * np);
  r.MinDirection.resize(3 * np);
  r.MaxDirection.resize(3 * np);
  r.Normals.resize(3 * np);
  r.StretchRatio.resize(np);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 512),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const Vec3& n = normal[i];
        const Vec3 t1 = AnyTangent(n), t2 = n.cross(t1);
        Eigen::Matrix2d D;
        const Mat3& L = lineField[i];
        D << t1.dot(L * t1), t1.dot(L * t2), t2.dot(L * t1), t2.dot(L * t2);
        const SymmetricEigen2 e = EigenDecompose(D);
        const Vec3 vmax = (e.Vectors(0, 1) * t1 + e.Vectors(1, 1) * t2).normalized();
        const Vec3 vmin = n.cross(vmax);
        double ratio = stretch[i][1] / stretch[i][0];
        if (opt.MaxStretch > 0.0)
        {
          ratio = std::min(ratio, opt.MaxStretch);
        }
        r.StretchRatio[i] = ratio;
        const Mat3 M = vmin * vmin.transpose() + ratio * ratio * vmax * vmax.transpose();
        PackSymmetric(M, r.Metric.Values.data() + 6 * i);
        for (int d = 0; d < 3; ++d)
        {
          r.MinDirection[3 * i + d] = vmin[d];
          r.MaxDirection[3 * i + d] = vmax[d];
          r.Normals[3 * i + d] = n[d];
        }
      }
    });
}
} // namespace

std::vector<double> SurfaceVertexNormals(const SimplexMesh& s)
{
  const double diag = ValidateSurface(s, SurfaceCurvatureMetricOptions());
  const std::vector<Vec3> normal = VertexNormals(s, diag);
  std::vector<double> flat(3 * normal.size());
  for (std::size_t i = 0; i < normal.size(); ++i)
    Eigen::Map<Vec3>(flat.data() + 3 * i) = normal[i];
  return flat;
}

SurfaceCurvatureMetricResult SurfaceCurvatureMetric(const SimplexMesh& s,
  const SurfaceCurvatureMetricOptions& opt)
{
  const double diag = ValidateSurface(s, opt);
  const std::vector<Vec3> normal = VertexNormals(s, diag);
  SurfaceCurvatureMetricResult r;
  std::vector<std::int32_t> vfOffset, vfList;
  VertexFaces(s, vfOffset, vfList);
  const std::vector<Vec3> cornerNormal =
    CornerNormals(s, normal, opt.CreaseAngle, vfOffset, vfList, r.NumCreaseEdges);
  std::vector<Mat3> faceForm;
  std::vector<double> faceWeight;
  FaceShapeOperators(s, cornerNormal, faceForm, faceWeight);
  r.CurvatureFloor = opt.CurvatureThreshold / diag;
  std::vector<Eigen::Vector2d> stretch;
  std::vector<Mat3> lineField;
  PrincipalCurvatures(s, normal, faceForm, faceWeight, vfOffset, vfList, r, stretch, lineField);
  if (opt.SmoothingIterations > 0)
  {
    SmoothStretchAndDirections(s, opt.SmoothingIterations, stretch, lineField);
  }
  AssembleMetric(s, opt, normal, stretch, lineField, r);
  return r;
}

} // namespace av
