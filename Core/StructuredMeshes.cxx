#include "StructuredMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace av
{

namespace
{
double Det3(const double* p0, const double* p1, const double* p2, const double* p3)
{
  const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  const double c[3] = { p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2] };
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
    a[2] * (b[0] * c[1] - b[1] * c[0]);
}

void CheckBox(int n, double lo, double hi, const char* axis)
{
  if (n < 2)
  {
    throw InputError(std::string("structured grid: need at least 2 vertices along ") + axis);
  }
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi))
  {
    throw InputError(std::string("structured grid: empty or invalid extent along ") + axis);
  }
}
} // namespace

SimplexMesh MakeKuhnTetGrid(int nx, int ny, int nz, const double lo[3], const double hi[3])
{
  CheckBox(nx, lo[0], hi[0], "x");
  CheckBox(ny, lo[1], hi[1], "y");
  CheckBox(nz, lo[2], hi[2], "z");
  SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 3;
  const std::size_t np = static_cast<std::size_t>(nx) * ny * nz;
  mesh.Points.resize(3 * np);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        double* p = mesh.Points.data() + 3 * (i + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k));
        // Exact end points: no round-off at hi.
        p[0] = i == nx - 1 ? hi[0] : lo[0] + (hi[0] - lo[0]) * i / (nx - 1);
        p[1] = j == ny - 1 ? hi[1] : lo[1] + (hi[1] - lo[1]) * j / (ny - 1);
        p[2] = k == nz - 1 ? hi[2] : lo[2] + (hi[2] - lo[2]) * k / (nz - 1);
      }
    }
  }
  // The 6 monotone lattice paths from corner 000 to 111; odd permutations get two vertices
  // swapped so that every tet is positively oriented.
  static const int perms[6][3] = { { 0, 1, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 0, 2, 1 }, { 2, 1, 0 },
    { 1, 0, 2 } };
  const std::size_t ncubes = static_cast<std::size_t>(nx - 1) * (ny - 1) * (nz - 1);
  mesh.Cells.reserve(ncubes * 24);
  const std::int64_t stride[3] = { 1, nx, static_cast<std::int64_t>(nx) * ny };
  for (int k = 0; k + 1 < nz; ++k)
  {
    for (int j = 0; j + 1 < ny; ++j)
    {
      for (int i = 0; i + 1 < nx; ++i)
      {
        const std::int64_t base = i + stride[1] * j + stride[2] * k;
        for (int t = 0; t < 6; ++t)
        {
          std::int64_t v[4];
          v[0] = base;
          v[1] = v[0] + stride[perms[t][0]];
          v[2] = v[1] + stride[perms[t][1]];
          v[3] = v[2] + stride[perms[t][2]];
          if (t >= 3)
          {
            std::swap(v[1], v[2]);
          }
          for (int q = 0; q < 4; ++q)
          {
            mesh.Cells.push_back(static_cast<std::int32_t>(v[q]));
          }
        }
      }
    }
  }
  return mesh;
}

SimplexMesh MakeTriangleGrid(int nx, int ny, const double lo[2], const double hi[2])
{
  CheckBox(nx, lo[0], hi[0], "x");
  CheckBox(ny, lo[1], hi[1], "y");
  SimplexMesh mesh;
  mesh.AmbientDim = 2;
  mesh.SimplexDim = 2;
  mesh.Points.resize(2 * static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      double* p = mesh.Points.data() + 2 * (i + static_cast<std::size_t>(nx) * j);
      p[0] = i == nx - 1 ? hi[0] : lo[0] + (hi[0] - lo[0]) * i / (nx - 1);
      p[1] = j == ny - 1 ? hi[1] : lo[1] + (hi[1] - lo[1]) * j / (ny - 1);
    }
  }
  mesh.Cells.reserve(6 * static_cast<std::size_t>(nx - 1) * (ny - 1));
  for (int j = 0; j + 1 < ny; ++j)
  {
    for (int i = 0; i + 1 < nx; ++i)
    {
      const std::int32_t a = i + nx * j, b = a + 1, c = a + nx, d = c + 1;
      // Counter-clockwise: (a, b, d) and (a, d, c).
      mesh.Cells.insert(mesh.Cells.end(), { a, b, d, a, d, c });
    }
  }
  return mesh;
}

std::vector<std::int32_t> UniqueEdges(const SimplexMesh& mesh)
{
  const int nv = mesh.VerticesPerCell();
  std::vector<std::uint64_t> keys;
  keys.reserve(mesh.NumCells() * nv * (nv - 1) / 2);
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* cell = mesh.Cell(c);
    for (int a = 0; a < nv; ++a)
    {
      for (int b = a + 1; b < nv; ++b)
      {
        std::uint32_t u = static_cast<std::uint32_t>(cell[a]), w = static_cast<std::uint32_t>(cell[b]);
        if (u > w)
        {
          std::swap(u, w);
        }
        keys.push_back((static_cast<std::uint64_t>(u) << 32) | w);
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<std::int32_t> edges(2 * keys.size());
  for (std::size_t e = 0; e < keys.size(); ++e)
  {
    edges[2 * e] = static_cast<std::int32_t>(keys[e] >> 32);
    edges[2 * e + 1] = static_cast<std::int32_t>(keys[e] & 0xffffffffu);
  }
  return edges;
}

std::vector<char> BoundaryVertexMask(const SimplexMesh& mesh)
{
  std::vector<char> mask(mesh.NumPoints(), 0);
  const int nv = mesh.VerticesPerCell();
  if (mesh.SimplexDim == 3)
  {
    std::vector<std::array<std::int32_t, 3>> faces;
    faces.reserve(4 * mesh.NumCells());
    for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    {
      const std::int32_t* cell = mesh.Cell(c);
      for (int skip = 0; skip < 4; ++skip)
      {
        std::array<std::int32_t, 3> f;
        int q = 0;
        for (int a = 0; a < 4; ++a)
        {
          if (a != skip)
          {
            f[q++] = cell[a];
          }
        }
        std::sort(f.begin(), f.end());
        faces.push_back(f);
      }
    }
    std::sort(faces.begin(), faces.end());
    for (std::size_t i = 0; i < faces.size();)
    {
      std::size_t j = i + 1;
      while (j < faces.size() && faces[j] == faces[i])
      {
        ++j;
      }
      if (j - i == 1)
      {
        for (std::int32_t v : faces[i])
        {
          mask[v] = 1;
        }
      }
      i = j;
    }
  }
  else
  {
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * mesh.NumCells());
    for (std::size_t c = 0; c < mesh.NumCells(); ++c)
    {
      const std::int32_t* cell = mesh.Cell(c);
      for (int a = 0; a < nv; ++a)
      {
        std::uint32_t u = static_cast<std::uint32_t>(cell[a]);
        std::uint32_t w = static_cast<std::uint32_t>(cell[(a + 1) % nv]);
        if (u > w)
        {
          std::swap(u, w);
        }
        keys.push_back((static_cast<std::uint64_t>(u) << 32) | w);
      }
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();)
    {
      std::size_t j = i + 1;
      while (j < keys.size() && keys[j] == keys[i])
      {
        ++j;
      }
      if (j - i == 1)
      {
        mask[keys[i] >> 32] = 1;
        mask[keys[i] & 0xffffffffu] = 1;
      }
      i = j;
    }
  }
  return mask;
}

double CellMeasure(const SimplexMesh& mesh, std::size_t cell)
{
  const std::int32_t* c = mesh.Cell(cell);
  if (mesh.SimplexDim == 3)
  {
    return Det3(mesh.Point(c[0]), mesh.Point(c[1]), mesh.Point(c[2]), mesh.Point(c[3])) / 6.0;
  }
  const int d = mesh.AmbientDim;
  const double* p0 = mesh.Point(c[0]);
  const double* p1 = mesh.Point(c[1]);
  const double* p2 = mesh.Point(c[2]);
  if (d == 2)
  {
    return 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
  }
  const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  const double n[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

} // namespace av
