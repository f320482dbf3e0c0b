// SPDX-License-Identifier: BSD-3-Clause
// ParticleNeighborListsInternal: the particle sampler's two-level Verlet lists (outer lists from
// a grid on the particles' principal coordinates, inner lists refiltered from them).
#ifndef av_ParticleNeighborListsInternal_h
#define av_ParticleNeighborListsInternal_h

#include "FixedBlockSumsInternal.h"
#include "PrincipalGridInternal.h"
#include "SamplerDimensions.h"

#include <Eigen/Dense>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace av
{
namespace sampling
{

/**
 * Two-level Verlet lists of N particles in R^D. The inner lists (radius Cutoff + Skin, used by
 * the energy) are refiltered from the outer lists (radius Cutoff + Skin + OuterSkin, grid)
 * when two particles may have closed in by more than Skin; the outer lists are rebuilt when
 * that may be by more than OuterSkin since their build, so every pair closer than Cutoff stays
 * listed. Lists are sorted by index, so results do not depend on when they were rebuilt.
 */
template <int D>
class ParticleNeighborLists
{
  using Vec = PointVector<D>;

public:
  explicit ParticleNeighborLists(int dim)
    : Dim(dim)
  {
  }

  void Resize(std::size_t n)
  {
    N = n;
    Outer.resize(N);
    InnerCount.assign(N, 0);
  }

  /// Radii of the lists; forces a rebuild.
  void SetRadii(double cutoff, double skin, double outerSkin)
  {
    Cutoff = cutoff;
    Skin = skin;
    OuterSkin = outerSkin;
    ListPositions.clear();
    OuterPositions.clear();
  }

  /// Makes the inner lists valid for the positions x (rebuilding what the moves require).
  void Update(const std::vector<double>& x)
  {
    if (TwoLargestMoves(x, ListPositions) <= Skin)
      return;
    if (TwoLargestMoves(x, OuterPositions) > OuterSkin)
      BuildOuter(x);
    ListPositions = x;
    RefilterInner(x);
  }

  /// Particle p's inner list (InnerCount(p) particle indices, ascending).
  const std::uint32_t* InnerList(std::size_t p) const { return Inner.data() + OuterStart[p]; }
  std::size_t InnerCountOf(std::size_t p) const { return InnerCount[p]; }
  int OuterBuilds() const { return Rebuilds; }

  /// Mean number of neighbors closer than the cutoff.
  double MeanNeighbors(const std::vector<double>& x)
  {
    Update(x);
    std::size_t total = 0;
    for (std::size_t p = 0; p < N; ++p)
      for (std::uint32_t j = 0; j < InnerCount[p]; ++j)
      {
        const std::uint32_t q = Inner[OuterStart[p] + j];
        double d2 = 0.0;
        for (int d = 0; d < Dim; ++d)
          d2 += std::pow(x[p * static_cast<std::size_t>(Dim) + static_cast<std::size_t>(d)] -
              x[q * static_cast<std::size_t>(Dim) + static_cast<std::size_t>(d)],
            2);
        total += d2 < Cutoff * Cutoff ? 1 : 0;
      }
    return static_cast<double>(total) / static_cast<double>(N);
  }

private:
  const double* At(const std::vector<double>& x, std::size_t p) const
  {
    return x.data() + p * static_cast<std::size_t>(Dim);
  }

  /// Sum of the two largest displacements between `x` and `ref` (no pair can have closed in
  /// by more than this); infinity when `ref` is unset.
  double TwoLargestMoves(const std::vector<double>& x, const std::vector<double>& ref)
  {
    if (ref.size() != x.size())
      return std::numeric_limits<double>::infinity();
    // Per block of particles its two largest squared displacements, then of all blocks.
    const std::size_t perBlock =
      std::max<std::size_t>(1, FixedBlockSums::kBlock / static_cast<std::size_t>(Dim));
    const std::size_t blocks = (N + perBlock - 1) / perBlock;
    MovePartials.resize(2 * blocks);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& r)
      {
        for (std::size_t b = r.begin(); b != r.end(); ++b)
        {
          double m1 = 0.0, m2 = 0.0;
          for (std::size_t p = b * perBlock, e = std::min(N, (b + 1) * perBlock); p < e; ++p)
          {
            const Eigen::Map<const Vec> u(At(x, p), Dim);
            const Eigen::Map<const Vec> v(At(ref, p), Dim);
            const double d2 = (u - v).squaredNorm();
            if (d2 > m2)
            {
              m2 = std::min(d2, m1);
              m1 = std::max(d2, m1);
            }
          }
          MovePartials[2 * b] = m1;
          MovePartials[2 * b + 1] = m2;
        }
      });
    double m1 = 0.0, m2 = 0.0; // two largest squared displacements
    for (double d2 : MovePartials)
      if (d2 > m2)
      {
        m2 = std::min(d2, m1);
        m1 = std::max(d2, m1);
      }
    return std::sqrt(m1) + std::sqrt(m2);
  }

  /// Outer lists: all pairs closer than Cutoff + Skin + OuterSkin at the positions x, each
  /// sorted by particle index (the summation order then does not depend on the search). The
  /// candidates come from a uniform grid on the particles' 3 principal coordinates (a kd-tree
  /// over all Dim coordinates visits many more leaves at this radius).
  void BuildOuter(const std::vector<double>& x)
  {
    ++Rebuilds;
    OuterPositions = x;
    const double r = Cutoff + Skin + OuterSkin;
    const auto at = [&](std::size_t p) { return At(x, p); };
    const AxesMatrix<D> axes = PrincipalAxes<D, Eigen::MatrixXd>(N, Dim, at);
    // Projected coordinates and the grid (cell side a bit over r: neighbors are in the
    // adjacent cells despite round-off).
    Proj.resize(3 * N);
    for (int a = 0; a < 3; ++a)
      GridLo[a] = 0.0;
    double hi[3] = { 0.0, 0.0, 0.0 };
    ProjectedBounds<D>(axes, N, Dim, at, GridLo, hi, Proj.data());
    GridSide = GridCellSide(GridLo, hi, r, N, GridCells);
    SortIntoGrid(x);
    CollectCandidates(x, r * r);
    OuterStart.resize(N + 1);
    OuterStart[0] = 0;
    for (std::size_t p = 0; p < N; ++p)
      OuterStart[p + 1] = OuterStart[p] + Outer[p].size();
    Inner.resize(OuterStart[N]);
  }

  /// Grid coordinate of particle p along axis a.
  long long GridCoord(std::size_t p, int a) const
  {
    return std::min(
      GridCells[a] - 1, static_cast<long long>((Proj[3 * p + a] - GridLo[a]) / GridSide));
  }

  /// The grid as CSR (GridStart, GridItems) with the positions copied in grid order (GridX):
  /// the candidate scan then reads them in a row.
  void SortIntoGrid(const std::vector<double>& x)
  {
    const long long* n = GridCells;
    const auto numCells = static_cast<std::size_t>(n[0] * n[1] * n[2]);
    GridStart.assign(numCells + 1, 0);
    ParticleCell.resize(N);
    for (std::size_t p = 0; p < N; ++p)
    {
      const long long c = (GridCoord(p, 0) * n[1] + GridCoord(p, 1)) * n[2] + GridCoord(p, 2);
      ParticleCell[p] = static_cast<std::uint32_t>(c);
      ++GridStart[static_cast<std::size_t>(c) + 1];
    }
    for (std::size_t c = 0; c < numCells; ++c)
      GridStart[c + 1] += GridStart[c];
    GridItems.resize(N);
    GridX.resize(x.size());
    std::vector<std::uint32_t> fill(GridStart.begin(), GridStart.end() - 1);
    for (std::size_t p = 0; p < N; ++p)
    {
      const std::uint32_t t = fill[ParticleCell[p]]++;
      GridItems[t] = static_cast<std::uint32_t>(p);
      std::copy_n(At(x, p), Dim, GridX.data() + t * static_cast<std::size_t>(Dim));
    }
  }

  /// Outer[p] for every particle: the 3 x 3 x 3 grid cells around the particle's, as 9 runs
  /// of consecutive cells; full distances on grid-ordered positions, stored branch-free.
  void CollectCandidates(const std::vector<double>& x, double r2)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& rg)
      {
        // Local copies: the buffer's reallocations would make the compiler reload members.
        const long long n[3] = { GridCells[0], GridCells[1], GridCells[2] };
        const std::uint32_t* gridStart = GridStart.data();
        const std::uint32_t* gridItems = GridItems.data();
        const double* gridX = GridX.data();
        std::vector<std::uint32_t> buffer; // per chunk, grows to the largest neighborhood
        for (std::size_t p = rg.begin(); p != rg.end(); ++p)
        {
          const Eigen::Map<const Vec> xp(At(x, p), Dim);
          long long c[3];
          for (int a = 0; a < 3; ++a)
            c[a] = GridCoord(p, a);
          const long long k0 = std::max(0LL, c[2] - 1), k1 = std::min(n[2] - 1, c[2] + 1);
          std::size_t count = 0;
          for (long long i = std::max(0LL, c[0] - 1); i <= std::min(n[0] - 1, c[0] + 1); ++i)
            for (long long j = std::max(0LL, c[1] - 1); j <= std::min(n[1] - 1, c[1] + 1); ++j)
            {
              const auto row = static_cast<std::size_t>((i * n[1] + j) * n[2]);
              const std::uint32_t t0 = gridStart[row + static_cast<std::size_t>(k0)];
              const std::uint32_t t1 = gridStart[row + static_cast<std::size_t>(k1) + 1];
              if (buffer.size() < count + (t1 - t0))
                buffer.resize(2 * (count + (t1 - t0)));
              for (std::uint32_t t = t0; t < t1; ++t)
              {
                const Eigen::Map<const Vec> xq(gridX + t * static_cast<std::size_t>(Dim), Dim);
                const std::uint32_t q = gridItems[t];
                buffer[count] = q;
                count += ((xp - xq).squaredNorm() < r2) & (q != p) ? 1 : 0;
              }
            }
          auto& list = Outer[p];
          list.assign(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(count));
          std::sort(list.begin(), list.end());
        }
      });
  }

  /// Inner lists from the outer ones: into the outer list's slot (a superset), branch-free.
  void RefilterInner(const std::vector<double>& x)
  {
    const double r = Cutoff + Skin;
    const double r2 = r * r;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N),
      [&](const tbb::blocked_range<std::size_t>& rg)
      {
        for (std::size_t p = rg.begin(); p != rg.end(); ++p)
        {
          const Eigen::Map<const Vec> xp(At(x, p), Dim);
          std::uint32_t* out = Inner.data() + OuterStart[p];
          std::uint32_t count = 0;
          for (std::uint32_t q : Outer[p])
          {
            const Eigen::Map<const Vec> xq(At(x, q), Dim);
            out[count] = q;
            count += (xp - xq).squaredNorm() < r2 ? 1 : 0;
          }
          InnerCount[p] = count;
        }
      });
  }

  const int Dim;
  std::size_t N = 0;
  double Cutoff = 5.0;
  double Skin = 1.0;
  double OuterSkin = 2.0;
  int Rebuilds = 0;
  std::vector<double> ListPositions;  // positions at the last inner list build
  std::vector<double> OuterPositions; // positions at the last outer list build
  std::vector<std::vector<std::uint32_t>> Outer;
  /// Inner lists, CSR in the outer lists' layout: particle p's are the first InnerCount[p]
  /// of Inner[OuterStart[p] ..].
  std::vector<std::size_t> OuterStart;
  std::vector<std::uint32_t> Inner, InnerCount;
  std::vector<double> Proj;  // principal coordinates (3 per particle)
  std::vector<double> GridX; // positions in grid order
  std::vector<std::uint32_t> GridStart, GridItems, ParticleCell; // outer-list grid (CSR)
  double GridLo[3] = { 0.0, 0.0, 0.0 }; // grid origin (principal coordinates)
  double GridSide = 1.0;                // grid cell side
  long long GridCells[3] = { 1, 1, 1 }; // grid cells per axis
  std::vector<double> MovePartials;     // per block: its two largest squared moves
};

} // namespace sampling
} // namespace av

#endif
