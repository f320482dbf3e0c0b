// SPDX-License-Identifier: BSD-3-Clause
#include "TetMesher.h"
#include "MeshTopology.h"

#include "SurfaceGenerators.h"

#ifndef TETLIBRARY
#define TETLIBRARY // the Debian library is built with it; the header leaves it commented out
#endif
#include <tetgen.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <cerrno>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace av
{
namespace
{
/// TetGen's -a bound over the volume of a regular tet of edge h (calibrated, see MeshWithTarget).
constexpr double kVolumeFactor = 2.0;
/// Measured: with that bound and -q1.5, TetGen puts about 0.78 sqrt(2) V / h^3 interior
/// vertices in a volume V (balls and boxes, 10^3..10^5 vertices).
constexpr double kInteriorDensity = 0.78;

std::string TetGenErrorText(int code)
{
  switch (code)
  {
    case 1:
      return "TetGen ran out of memory";
    case 2:
      return "TetGen hit an internal error";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "the surface has a feature (edge, gap) too small for TetGen's tolerance";
    case 5:
      return "two surface triangles are nearly coincident";
    case 10:
      return "TetGen rejected the input";
    default:
      return "TetGen failed with code " + std::to_string(code);
  }
}

void ValidateClosedSurface(const SimplexMesh& s)
{
  const std::string who = "TetrahedralizeClosedSurface: ";
  if (s.AmbientDim != 3 || s.SimplexDim != 2)
  {
    throw InputError(who + "expected a triangle surface in 3D (AmbientDim 3, SimplexDim 2)");
  }
  if (s.Points.size() % 3 != 0 || s.Cells.size() % 3 != 0)
  {
    throw InputError(who + "point or cell array size is not a multiple of 3");
  }
  const std::size_t np = s.NumPoints(), nc = s.NumCells();
  if (np < 4 || nc < 4)
  {
    throw InputError(who + "the surface is empty or too small to enclose a volume");
  }
  if (np > 0x7fffffff / 2)
  {
    throw InputError(who + "too many points for TetGen's int indices");
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (std::size_t i = 0; i < np; ++i)
  {
    const Eigen::Map<const Eigen::Vector3d> p(s.Point(i));
    if (!p.allFinite())
    {
      throw InputError(who + "point " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diag2 = (hi - lo).squaredNorm();
  std::vector<std::uint64_t> edges;
  std::vector<std::array<std::int32_t, 3>> tris(nc);
  edges.reserve(3 * nc);
  CheckCellIds(s, who, "triangle");
  for (std::size_t c = 0; c < nc; ++c)
  {
    const std::int32_t* t = s.Cell(c);
    const Eigen::Map<const Eigen::Vector3d> a(s.Point(t[0])), b(s.Point(t[1])), d(s.Point(t[2]));
    const double area2 = (b - a).cross(d - a).squaredNorm();
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(area2 > 1e-24 * diag2 * diag2))
    {
      throw InputError(who + "triangle " + std::to_string(c) + " is degenerate (zero area)");
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::uint64_t u = static_cast<std::uint32_t>(std::min(t[k], t[(k + 1) % 3]));
      const std::uint64_t v = static_cast<std::uint32_t>(std::max(t[k], t[(k + 1) % 3]));
      edges.push_back(u << 32 | v);
    }
    tris[c] = { t[0], t[1], t[2] };
    std::sort(tris[c].begin(), tris[c].end());
  }
  std::sort(tris.begin(), tris.end());
  if (std::adjacent_find(tris.begin(), tris.end()) != tris.end())
  {
    throw InputError(who + "the surface contains the same triangle twice");
  }
  std::sort(edges.begin(), edges.end());
  std::size_t open = 0, nonManifold = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    open += (j - i == 1);
    nonManifold += (j - i > 2);
    i = j;
  }
  if (open > 0 || nonManifold > 0)
  {
    throw InputError(who + "the surface is not closed and manifold: " + std::to_string(open) +
      " boundary edge(s), " + std::to_string(nonManifold) +
      " edge(s) shared by more than two triangles");
  }
}

/// Makes every tet positively oriented and drops unused points.
SimplexMesh FromTetGen(const tetgenio& out)
{
  SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  const std::size_t np = static_cast<std::size_t>(out.numberofpoints);
  const std::size_t nt = static_cast<std::size_t>(out.numberoftetrahedra);
  std::vector<std::int32_t> remap(np, -1);
  m.Cells.assign(out.tetrahedronlist, out.tetrahedronlist + 4 * nt);
  for (std::size_t i = 0; i < 4 * nt; ++i)
  {
    remap[static_cast<std::size_t>(m.Cells[i])] = 0;
  }
  std::int32_t next = 0;
  m.Points.reserve(3 * np);
  for (std::size_t i = 0; i < np; ++i)
  {
    if (remap[i] == 0)
    {
      remap[i] = next++;
      m.Points.insert(m.Points.end(), out.pointlist + 3 * i, out.pointlist + 3 * i + 3);
    }
  }
  for (std::size_t c = 0; c < nt; ++c)
  {
    std::int32_t* t = m.Cells.data() + 4 * c;
    for (int k = 0; k < 4; ++k)
    {
      t[k] = remap[static_cast<std::size_t>(t[k])];
    }
    const Eigen::Map<const Eigen::Vector3d> a(m.Point(t[0])), b(m.Point(t[1])),
      cc(m.Point(t[2])), d(m.Point(t[3]));
    if ((b - a).dot((cc - a).cross(d - a)) < 0.0)
    {
      std::swap(t[2], t[3]);
    }
  }
  return m;
}

/// Meshes surfaceOf(h) (kept unsplit, TetGen -Y: fast and the boundary stays exact) with a
/// volume bound derived from h. h is chosen so that the predicted vertex count, interior
/// (calibrated) plus surface (exact, surfaceCount(h)), hits the target; one corrected
/// re-run when the result misses by more than 8 %.
template <class SurfaceOfSpacing, class SurfaceCount>
SimplexMesh MeshWithTarget(
  double volume, std::size_t target, SurfaceOfSpacing surfaceOf, SurfaceCount surfaceCount)
{
  const double n = static_cast<double>(target);
  double density = kInteriorDensity;
  auto interiorOf = [&](double h) { return density * std::sqrt(2.0) * volume / (h * h * h); };
  auto solveSpacing = [&]() {
    double h = std::cbrt(std::sqrt(2.0) * volume / n);
    for (int it = 0; it < 60; ++it)
    {
      h *= std::pow((interiorOf(h) + surfaceCount(h)) / n, 0.25); // damped: the surface count is a step function
    }
    return h;
  };
  SimplexMesh mesh;
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    const double h = solveSpacing();
    TetMeshOptions o;
    o.DetectSelfIntersections = false; // generated surfaces are valid by construction
    o.RadiusEdgeRatio = 1.5;
    o.PreserveSurface = true;
    o.MaxVolume = kVolumeFactor * h * h * h / (6.0 * std::sqrt(2.0));
    mesh = TetrahedralizeClosedSurface(surfaceOf(h), o);
    const double ratio = static_cast<double>(mesh.NumPoints()) / n;
    if (std::abs(ratio - 1.0) < 0.08)
    {
      break;
    }
    // Re-calibrate the interior density on this very domain and solve again.
    const double interior = static_cast<double>(mesh.NumPoints()) - surfaceCount(h);
    density *= std::max(0.2, std::min(5.0, std::max(1.0, interior) / std::max(1.0, interiorOf(h))));
  }
  return mesh;
}
} // namespace

SimplexMesh TetrahedralizeClosedSurface(
  const SimplexMesh& triangleSurface, const TetMeshOptions& options)
{
  ValidateClosedSurface(triangleSurface);
  if (!(options.MaxVolume >= 0.0) || !std::isfinite(options.MaxVolume))
  {
    throw InputError("TetrahedralizeClosedSurface: MaxVolume must be >= 0 and finite");
  }
  if (options.RadiusEdgeRatio != 0.0 && !(options.RadiusEdgeRatio > 1.0))
  {
    throw InputError(
      "TetrahedralizeClosedSurface: RadiusEdgeRatio must be > 1 (or 0 to disable refinement)");
  }
  if (!(options.MinDihedral >= 0.0 && options.MinDihedral < 30.0))
  {
    throw InputError("TetrahedralizeClosedSurface: MinDihedral must be in [0, 30) degrees");
  }

  auto fill = [&](tetgenio& in) {
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(triangleSurface.NumPoints());
    in.pointlist = new REAL[triangleSurface.Points.size()];
    std::copy(triangleSurface.Points.begin(), triangleSurface.Points.end(), in.pointlist);
    const std::size_t nc = triangleSurface.NumCells();
    in.numberoffacets = static_cast<int>(nc);
    in.facetlist = new tetgenio::facet[nc];
    for (std::size_t c = 0; c < nc; ++c)
    {
      tetgenio::facet& f = in.facetlist[c];
      f.numberofpolygons = 1;
      f.polygonlist = new tetgenio::polygon[1];
      f.numberofholes = 0;
      f.holelist = nullptr;
      f.polygonlist[0].numberofvertices = 3;
      f.polygonlist[0].vertexlist = new int[3];
      std::copy(
        triangleSurface.Cell(c), triangleSurface.Cell(c) + 3, f.polygonlist[0].vertexlist);
    }
  };
  if (options.DetectSelfIntersections)
  {
    tetgenio in, out;
    fill(in);
    char diagnose[] = "pdzQ";
    try
    {
      tetrahedralize(diagnose, &in, &out);
    }
    catch (int code)
    {
      throw InputError("TetrahedralizeClosedSurface: " + TetGenErrorText(code));
    }
    if (out.numberoftrifaces > 0)
    {
      throw InputError("TetrahedralizeClosedSurface: the surface intersects itself (" +
        std::to_string(out.numberoftrifaces) + " triangles involved)");
    }
  }
  tetgenio in, out;
  fill(in);

  std::string sw = "pz";
  char buf[64];
  if (options.RadiusEdgeRatio > 0.0)
  {
    std::snprintf(buf, sizeof(buf), "q%.9g", options.RadiusEdgeRatio);
    sw += buf;
    if (options.MinDihedral > 0.0)
    {
      std::snprintf(buf, sizeof(buf), "/%.9g", options.MinDihedral);
      sw += buf;
    }
  }
  if (options.MaxVolume > 0.0)
  {
    std::snprintf(buf, sizeof(buf), "a%.17f", options.MaxVolume);
    sw += buf;
  }
  if (options.PreserveSurface)
  {
    sw += "Y";
  }
  if (options.Quiet)
  {
    sw += "Q";
  }
  std::vector<char> switches(sw.begin(), sw.end());
  switches.push_back('\0');
  try
  {
    tetrahedralize(switches.data(), &in, &out);
  }
  catch (int code)
  {
    throw InputError("TetrahedralizeClosedSurface: " + TetGenErrorText(code));
  }
  if (out.numberoftetrahedra <= 0 || out.tetrahedronlist == nullptr)
  {
    throw InputError("TetrahedralizeClosedSurface: TetGen produced no tetrahedron (is the "
                     "surface flat or inside out?)");
  }
  return FromTetGen(out);
}

SimplexMesh TetrahedralizeBox(const double lo[3], const double hi[3], std::size_t targetVertices)
{
  double size[3];
  for (int d = 0; d < 3; ++d)
  {
    size[d] = hi[d] - lo[d];
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) || !(size[d] > 0.0))
    {
      throw InputError("TetrahedralizeBox: need finite lo < hi on every axis");
    }
  }
  if (targetVertices < 8 || targetVertices > 50000000)
  {
    throw InputError("TetrahedralizeBox: targetVertices must be in [8, 5e7]");
  }
  auto intervals = [&](double h, int n[3]) {
    for (int d = 0; d < 3; ++d)
    {
      n[d] = static_cast<int>(std::max(1.0, std::min(1e5, std::round(size[d] / h))));
    }
  };
  return MeshWithTarget(
    size[0] * size[1] * size[2], targetVertices,
    [&](double h) {
      int n[3];
      intervals(h, n);
      return MakeBoxSurface(lo, hi, n);
    },
    [&](double h) {
      int n[3];
      intervals(h, n);
      return static_cast<double>(n[0] + 1) * (n[1] + 1) * (n[2] + 1) -
        static_cast<double>(n[0] - 1) * (n[1] - 1) * (n[2] - 1);
    });
}

SimplexMesh TetrahedralizeSphere(double radius, std::size_t targetVertices)
{
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    throw InputError("TetrahedralizeSphere: radius must be positive and finite");
  }
  if (targetVertices < 20 || targetVertices > 50000000)
  {
    throw InputError("TetrahedralizeSphere: targetVertices must be in [20, 5e7]");
  }
  const double pi = 3.14159265358979323846;
  // Surface edge about h: a triangle lattice has sqrt(3)/2 h^2 of area per vertex, and a
  // geodesic sphere of frequency f has 10 f^2 + 2 vertices.
  auto frequency = [&](double h) {
    const double nSurface = 4.0 * pi * radius * radius / (std::sqrt(3.0) / 2.0 * h * h);
    return static_cast<int>(std::max(1.0, std::min(4096.0, std::round(std::sqrt(nSurface / 10.0)))));
  };
  return MeshWithTarget(
    4.0 / 3.0 * pi * radius * radius * radius, targetVertices,
    [&](double h) { return MakeGeodesicSphere(radius, frequency(h)); },
    [&](double h) {
      const double f = frequency(h);
      return 10.0 * f * f + 2.0;
    });
}

double EnclosedVolume(const SimplexMesh& surface)
{
  double volume = 0;
  for (std::size_t c = 0; c < surface.NumCells(); ++c)
  {
    const double* a = surface.Point(surface.Cell(c)[0]);
    const double* b = surface.Point(surface.Cell(c)[1]);
    const double* d = surface.Point(surface.Cell(c)[2]);
    volume += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                a[2] * (b[0] * d[1] - b[1] * d[0])) /
      6.0;
  }
  return volume;
}

double MaxVolumeForVertexCount(const SimplexMesh& surface, std::size_t targetVertices)
{
  return std::abs(EnclosedVolume(surface)) / (5.0 * static_cast<double>(targetVertices));
}

} // namespace av

namespace av
{

namespace
{
/// All `size` bytes through `io` (read or write; retried on EINTR), false on an error or an
/// early end.
template <typename Buffer, typename Io>
bool TransferAll(int fd, Buffer* p, std::size_t size, Io io)
{
  while (size > 0)
  {
    const ssize_t n = io(fd, p, size);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool WriteAll(int fd, const void* data, std::size_t size)
{
  return TransferAll(fd, static_cast<const char*>(data), size, ::write);
}

bool ReadAll(int fd, void* data, std::size_t size)
{
  return TransferAll(fd, static_cast<char*>(data), size, ::read);
}

/// The tets of a TetGen run on `points` (which must not add a point), as a mesh of `points`.
SimplexMesh TetsOfPoints(const std::vector<double>& points, const tetgenio& out, const char* what)
{
  const std::size_t np = points.size() / 3;
  if (out.numberoftetrahedra <= 0 || out.tetrahedronlist == nullptr)
    throw InputError(std::string(what) +
      ": TetGen produced no tetrahedron (are the points "
      "coplanar?)");
  // TetGen drops repeated points and numbers the rest anew: map its points back to the first
  // input point at the same position.
  std::map<std::array<double, 3>, std::int32_t> firstAt;
  for (std::size_t i = np; i-- > 0;)
    firstAt[{ points[3 * i], points[3 * i + 1], points[3 * i + 2] }] = static_cast<std::int32_t>(i);
  std::vector<std::int32_t> inputOf(static_cast<std::size_t>(out.numberofpoints));
  for (std::size_t i = 0; i < inputOf.size(); ++i)
  {
    const auto it =
      firstAt.find({ out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2] });
    if (it == firstAt.end())
      throw InputError(std::string(what) + ": TetGen added a point");
    inputOf[i] = it->second;
  }
  SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  m.Points = points;
  const std::size_t nt = static_cast<std::size_t>(out.numberoftetrahedra);
  const int corners = out.numberofcorners;
  m.Cells.resize(4 * nt);
  for (std::size_t c = 0; c < nt; ++c)
  {
    std::int32_t* t = m.Cells.data() + 4 * c;
    for (int k = 0; k < 4; ++k)
      t[k] = inputOf[static_cast<std::size_t>(
        out.tetrahedronlist[c * static_cast<std::size_t>(corners) + k])];
    const Eigen::Map<const Eigen::Vector3d> a(m.Point(t[0])), b(m.Point(t[1])), cc(m.Point(t[2])),
      d(m.Point(t[3]));
    if ((b - a).dot((cc - a).cross(d - a)) < 0.0)
      std::swap(t[2], t[3]);
  }
  return m;
}
} // namespace

SimplexMesh DelaunayOfPoints(const std::vector<double>& points)
{
  const std::size_t np = points.size() / 3;
  if (np < 4 || points.size() != 3 * np)
    throw InputError("DelaunayOfPoints: needs at least 4 points (3 values each)");
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(np);
  in.pointlist = new REAL[3 * np];
  std::copy(points.begin(), points.end(), in.pointlist);
  char switches[] = "zQ"; // zero-based, quiet: a plain Delaunay tetrahedralization
  try
  {
    tetrahedralize(switches, &in, &out);
  }
  catch (int code)
  {
    throw InputError("DelaunayOfPoints: " + TetGenErrorText(code));
  }
  return TetsOfPoints(points, out, "DelaunayOfPoints");
}

SimplexMesh ConstrainedDelaunayOfPoints(const std::vector<double>& points,
  const std::vector<std::int32_t>& faces)
{
  const std::size_t np = points.size() / 3;
  if (np < 4 || points.size() != 3 * np || faces.size() % 3 != 0)
    throw InputError("ConstrainedDelaunayOfPoints: needs at least 4 points (3 values each) and "
                     "faces of 3 ids each");
  for (const std::int32_t v : faces)
    if (v < 0 || static_cast<std::size_t>(v) >= np)
      throw InputError("ConstrainedDelaunayOfPoints: a face id is out of range");
  // Each face once (TetGen treats a repeated facet as two).
  std::vector<std::array<std::int32_t, 3>> unique;
  unique.reserve(faces.size() / 3);
  for (std::size_t f = 0; f < faces.size(); f += 3)
  {
    std::array<std::int32_t, 3> t{ faces[f], faces[f + 1], faces[f + 2] };
    std::sort(t.begin(), t.end());
    if (t[0] == t[1] || t[1] == t[2])
      throw InputError("ConstrainedDelaunayOfPoints: a face repeats a point");
    unique.push_back(t);
  }
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(np);
  in.pointlist = new REAL[3 * np];
  std::copy(points.begin(), points.end(), in.pointlist);
  const std::size_t nf = unique.size();
  in.numberoffacets = static_cast<int>(nf);
  in.facetlist = new tetgenio::facet[nf];
  for (std::size_t f = 0; f < nf; ++f)
  {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k)
      facet.polygonlist[0].vertexlist[k] = unique[f][static_cast<std::size_t>(k)];
  }
  // PLC, keep the convex hull (the faces are inside it, not its boundary), zero-based, quiet,
  // no Steiner point on the faces (Y) nor anywhere (S0).
  // TetGen 1.5 can crash (SIGSEGV in its memory release) instead of reporting an error on faces
  // that intersect in a way the caller did not detect: it runs in a child process, which sends
  // the cells back through a pipe, so that a crash becomes an InputError here.
  int fds[2];
  if (pipe(fds) != 0)
    throw InputError("ConstrainedDelaunayOfPoints: no pipe for the TetGen process");
  const pid_t child = fork();
  if (child < 0)
  {
    close(fds[0]);
    close(fds[1]);
    throw InputError("ConstrainedDelaunayOfPoints: no TetGen process (fork failed)");
  }
  if (child == 0)
  {
    close(fds[0]);
    std::int64_t count = -1; // -1: TetGen reported an error
    std::vector<std::int32_t> cells;
    char switches[] = "pczQYS0";
    try
    {
      tetrahedralize(switches, &in, &out);
      cells = TetsOfPoints(points, out, "ConstrainedDelaunayOfPoints").Cells;
      count = static_cast<std::int64_t>(cells.size());
    }
    catch (...)
    {
    }
    const bool ok = WriteAll(fds[1], &count, sizeof count) &&
      (count <= 0 || WriteAll(fds[1], cells.data(), cells.size() * sizeof(std::int32_t)));
    _exit(ok ? 0 : 1);
  }
  close(fds[1]);
  std::int64_t count = -2;
  bool ok = ReadAll(fds[0], &count, sizeof count);
  std::vector<std::int32_t> cells;
  if (ok && count > 0 && count % 4 == 0 && static_cast<std::uint64_t>(count) <= (1ull << 34))
  {
    cells.resize(static_cast<std::size_t>(count));
    ok = ReadAll(fds[0], cells.data(), cells.size() * sizeof(std::int32_t));
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  if (WIFSIGNALED(status))
    throw InputError("ConstrainedDelaunayOfPoints: TetGen crashed (signal " +
      std::to_string(WTERMSIG(status)) + "; intersecting faces?)");
  if (!ok || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || count <= 0 || cells.empty())
    throw InputError("ConstrainedDelaunayOfPoints: TetGen failed on these faces (intersecting "
                     "or coplanar points?)");
  for (const std::int32_t v : cells)
    if (v < 0 || static_cast<std::size_t>(v) >= np)
      throw InputError("ConstrainedDelaunayOfPoints: a bad cell from the TetGen process");
  SimplexMesh m;
  m.AmbientDim = 3;
  m.SimplexDim = 3;
  m.Points = points;
  m.Cells = std::move(cells);
  return m;
}

} // namespace av
