// SPDX-License-Identifier: BSD-3-Clause
#include "StructuredMeshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace av
{

namespace
{
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

/// n evenly spaced values from lo to hi, hi exact.
std::vector<double> EvenlySpaced(int n, double lo, double hi)
{
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    v[i] = i == n - 1 ? hi : lo + (hi - lo) * i / (n - 1);
  return v;
}

void CheckLevels(const std::vector<double>& v, const char* axis)
{
  if (v.size() < 2)
    throw InputError(std::string("structured grid: need at least 2 vertices along ") + axis);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || (i > 0 && !(v[i] > v[i - 1])))
      throw InputError(std::string("structured grid: coordinates along ") + axis +
        " must be finite and strictly increasing");
}
} // namespace

SimplexMesh MakeKuhnTetGrid(int nx, int ny, int nz, const double lo[3], const double hi[3])
{
  CheckBox(nx, lo[0], hi[0], "x");
  CheckBox(ny, lo[1], hi[1], "y");
  CheckBox(nz, lo[2], hi[2], "z");
  return MakeKuhnTetGrid(
    EvenlySpaced(nx, lo[0], hi[0]), EvenlySpaced(ny, lo[1], hi[1]), EvenlySpaced(nz, lo[2], hi[2]));
}

SimplexMesh MakeKuhnTetGrid(
  const std::vector<double>& xs, const std::vector<double>& ys, const std::vector<double>& zs)
{
  CheckLevels(xs, "x");
  CheckLevels(ys, "y");
  CheckLevels(zs, "z");
  const int nx = static_cast<int>(xs.size()), ny = static_cast<int>(ys.size()),
            nz = static_cast<int>(zs.size());
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
        p[0] = xs[i];
        p[1] = ys[j];
        p[2] = zs[k];
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




} // namespace av
