// SPDX-License-Identifier: BSD-3-Clause
// RunMeshingPipeline: the same result as its steps called one by one, no inverted element
// left on folded embeddings (input-space signed areas), moved flags that are exactly the
// sites that changed, fixed sites that never move, and aborts where the callback asks.
#include "AnisoTestChecks.h"
#include "FoldedTestCases.h"
#include "MeshingPipeline.h"
#include "SiteImprovement.h"
#include "VoronoiTestMeshes.h"

#include <algorithm>
#include <iostream>
#include <vector>

using namespace av_test;

namespace
{
bool SameSite(const av::SiteSet& a, const av::SiteSet& b, std::size_t i)
{
  return a.CellIds[i] == b.CellIds[i] &&
    std::equal(a.Bary.begin() + 4 * i, a.Bary.begin() + 4 * i + 4, b.Bary.begin() + 4 * i) &&
    std::equal(a.At(i), a.At(i) + a.Dim, b.At(i));
}

// The repair's options for the pipeline's.
av::DelaunayRepairOptions RepairOptions(const av::MeshingPipelineOptions& o)
{
  av::DelaunayRepairOptions ro;
  ro.MaxRounds = o.Repair ? o.MaxRepairRounds : 0;
  ro.RepairNonManifold = o.RepairNonManifold;
  return ro;
}

// The moved flags are the input sites that differ, the inserted sites come after them.
void CheckMoved(const av::SiteSet& s, const av::MeshingPipelineResult& r)
{
  const std::size_t n = s.NumSites();
  AV_CHECK(r.Moved.size() == n && r.Repaired.NumInputSites == n);
  AV_CHECK(r.Repaired.Sites.NumSites() == n + r.Repaired.NumInserted);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const bool same = SameSite(s, r.Repaired.Sites, i);
    AV_CHECK((r.Moved[i] != 0) == !same);
    changed += same ? 0 : 1;
  }
  AV_CHECK(r.NumMovedSites == changed);
}

// A folded square / cube: one improvement round (the defaults), then the repair of what is
// left, to no inverted element; the same as the steps one by one.
void CheckFolded(const FoldedCase& c, const char* what)
{
  const auto& [m, e, s] = c;
  av::MeshingPipelineOptions o;
  o.ValidDual = false; // the sequence checked below ends with the repair (TestValidDualMesh)
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(m, e, s, o);
  std::cout << what << ": moved " << r.NumMovedSites << " (ODT " << r.NumOdtMovedSites
            << "), slivers " << r.NumSlivers << ", inverted per repair round";
  for (std::size_t v : r.Repaired.InvertedPerRound)
    std::cout << " " << v;
  std::cout << ", inserted " << r.Repaired.NumInserted << std::endl;
  AV_CHECK(!r.Aborted && r.ImproveRoundsDone == 1);
  AV_CHECK(r.NumOdtMovedSites > 0 && r.NumMovedSites > 0);
  AV_CHECK(m.SimplexDim == 3 || r.NumSlivers == 0); // triangles have no slivers
  AV_CHECK(r.Repaired.InitialInverted > 0);         // the case exercises the repair
  // No inverted cell left; the non-manifold repair (default on) may stall on the folded cube,
  // never at the price of an inverted cell.
  AV_CHECK(r.Repaired.Delaunay.NumInverted == 0);
  AV_CHECK(r.Repaired.Converged || (r.Repaired.Stalled && r.Repaired.Delaunay.NumNonManifoldFaces > 0));
  AV_CHECK(NegativeCells(r.Repaired.Delaunay) == 0);
  CheckMoved(s, r);
  AV_CHECK(r.VoronoiSeconds >= 0.0 && r.DelaunaySeconds >= 0.0 && r.ImproveSeconds >= 0.0 &&
    r.RepairSeconds >= 0.0);

  // The steps one by one: RVD, RDT, one round of ImproveSites, then the repair (which
  // computes the RVD + RDT of the moved sites itself).
  const av::DelaunayRepairOptions ro = RepairOptions(o);
  const auto rvd0 = av::ComputeRestrictedVoronoi(m, e, s, ro.Voronoi);
  const auto rdt0 = av::ComputeRestrictedDelaunay(m, e, s, rvd0);
  av::SiteImprovementOptions io;
  io.OdtIterations = o.OdtIterations;
  const av::SiteImprovementResult im = av::ImproveSites(m, e, s, rvd0, rdt0, io);
  AV_CHECK(im.NumOdtMoved == r.NumOdtMovedSites && im.NumSlivers == r.NumSlivers);
  const av::DelaunayRepairResult steps = av::RepairRestrictedDelaunay(m, e, im.Sites, ro);
  AV_CHECK(steps.Sites.Coords == r.Repaired.Sites.Coords);
  AV_CHECK(steps.Sites.CellIds == r.Repaired.Sites.CellIds);
  AV_CHECK(steps.Delaunay.Cells == r.Repaired.Delaunay.Cells);
  AV_CHECK(steps.Voronoi.PieceMeasure == r.Repaired.Voronoi.PieceMeasure);
  AV_CHECK(steps.InvertedPerRound == r.Repaired.InvertedPerRound);

  // Deterministic.
  const av::MeshingPipelineResult again = av::RunMeshingPipeline(m, e, s, o);
  AV_CHECK(again.Repaired.Sites.Coords == r.Repaired.Sites.Coords);
  AV_CHECK(again.Repaired.Delaunay.Cells == r.Repaired.Delaunay.Cells && again.Moved == r.Moved);
}

void TestFolded()
{
  // 19 inverted triangles after the improvement round, 2 repair rounds.
  CheckFolded(FoldedSquare(0.2, 12.0, 60, 2), "folded square");
  // 6 inverted tets after the improvement round, 2 repair rounds.
  CheckFolded(FoldedCube(0.2, 8.0, 150, 3), "folded cube");
}

// Isotropic metric on the input mesh (the folded embedding then strongly disagrees with it).
av::MetricField UnitMetric(const av::SimplexMesh& m)
{
  av::MetricField metric;
  metric.Values.assign(6 * m.NumPoints(), 0.0);
  for (std::size_t i = 0; i < m.NumPoints(); ++i)
    metric.Values[6 * i] = metric.Values[6 * i + 1] = metric.Values[6 * i + 2] = 1.0;
  return metric;
}

// Mesh improvement at the end: on the folded cases without repair the dual has inverted cells;
// after it there are fewer, each moved site is located where its mesh vertex is (cell,
// barycentric and embedded coordinates agree with the new position), fixed sites stay, and the
// cells differ only where the improvement worked.
void CheckMeshImprovement(const FoldedCase& c, const char* what)
{
  const auto& [m, e, s] = c;
  const av::MetricField metric = UnitMetric(m);
  av::MeshingPipelineOptions o;
  o.Repair = false;
  o.ValidDual = false; // the improvement on an invalid dual (TestValidDualMesh replaces it)
  const av::MeshingPipelineResult plain = av::RunMeshingPipeline(m, e, s, o);
  o.Metric = &metric;
  std::vector<std::uint8_t> fixed(s.NumSites(), 0);
  fixed[0] = fixed[1] = 1;
  o.FixedSites = &fixed;
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(m, e, s, o);
  const av::RestrictedDelaunayMesh& d = r.Repaired.Delaunay;
  std::cout << what << ": inverted " << r.InvertedBeforeImprovement << " -> " << d.NumInverted
            << " (negative " << NegativeCells(d) << "), flips "
            << r.Improvement.NumFlips23 + r.Improvement.NumEdgeRemovals + r.Improvement.NumFlips22
            << ", moves " << r.Improvement.NumSmoothed << ", worst " << r.Improvement.WorstBefore
            << " -> " << r.Improvement.WorstAfter << " deg" << std::endl;
  AV_CHECK(r.Improvement.Passes > 0 && plain.Improvement.Passes == 0);
  AV_CHECK(r.InvertedBeforeImprovement > 0);
  AV_CHECK(r.InvertedBeforeImprovement == plain.Repaired.Delaunay.NumInverted);
  // Inverted cells whose vertices are all on open or non-manifold faces cannot be reached by
  // local operations: fewer or as many, never more, and the worst never drops.
  AV_CHECK(d.NumInverted <= r.InvertedBeforeImprovement);
  AV_CHECK(r.Improvement.WorstAfter >= r.Improvement.WorstBefore);
  AV_CHECK(d.Inverted.size() == d.NumCells() && d.CellElement.size() == d.NumCells());
  const int ad = d.AmbientDim, k = d.SimplexDim;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < s.NumSites(); ++i)
  {
    const av::SiteSet& rs = r.Repaired.Sites;
    AV_CHECK(!fixed[i] || r.Improvement.Moved[i] == 0);
    if (!r.Improvement.Moved[i])
      continue;
    ++moved;
    AV_CHECK(r.Moved[i] == 1);
    // The moved vertex is where its site is: barycentric interpolation in the site's cell.
    const std::int32_t* v = m.Cell(static_cast<std::size_t>(rs.CellIds[i]));
    for (int dd = 0; dd < ad; ++dd)
    {
      double x = 0.0;
      for (int a = 0; a <= k; ++a)
      {
        AV_CHECK(rs.Bary[4 * i + a] >= 0.0);
        x += rs.Bary[4 * i + a] * m.Point(v[a])[dd];
      }
      AV_CHECK_NEAR(x, d.Points[i * ad + dd], 1e-9);
      AV_CHECK_NEAR(rs.At(i)[dd], d.Points[i * ad + dd], 1e-9);
    }
  }
  AV_CHECK(moved == r.Improvement.NumSmoothed || moved <= r.Improvement.NumSmoothed);
  AV_CHECK(r.NumMovedSites ==
    static_cast<std::size_t>(std::count(r.Moved.begin(), r.Moved.end(), 1)));

  // With the repair (the defaults): valid before, valid after, and the worst element better.
  o.Repair = true;
  const av::MeshingPipelineResult rr = av::RunMeshingPipeline(m, e, s, o);
  std::cout << what << ", repaired and improved: worst " << rr.Improvement.WorstBefore << " -> "
            << rr.Improvement.WorstAfter << " deg, cells " << rr.Repaired.Delaunay.NumCells()
            << std::endl;
  AV_CHECK(rr.InvertedBeforeImprovement == 0 && rr.Repaired.Delaunay.NumInverted == 0);
  AV_CHECK(NegativeCells(rr.Repaired.Delaunay) == 0);
  AV_CHECK(rr.Improvement.WorstAfter > rr.Improvement.WorstBefore);
}

void TestMeshImprovementStep()
{
  CheckMeshImprovement(FoldedSquare(0.2, 12.0, 60, 2), "folded square, improved");
  CheckMeshImprovement(FoldedCube(0.2, 8.0, 150, 3), "folded cube, improved");
}

// No improvement round: the repair of the input sites; no repair: the first RDT as it is.
void TestPaperPipeline()
{
  const auto& [m, e, s] = FoldedSquare(0.2, 12.0, 60, 1);
  av::MeshingPipelineOptions o;
  o.ImproveRounds = 0;
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(m, e, s, o);
  const av::DelaunayRepairResult direct = av::RepairRestrictedDelaunay(m, e, s, RepairOptions(o));
  AV_CHECK(r.Repaired.Sites.Coords == direct.Sites.Coords);
  AV_CHECK(r.Repaired.Delaunay.Cells == direct.Delaunay.Cells);
  AV_CHECK(r.Repaired.Converged && r.Repaired.Delaunay.NumInverted == 0);
  AV_CHECK(r.NumMovedSites == 0 && r.NumOdtMovedSites == 0 && r.ImproveRoundsDone == 0);
  CheckMoved(s, r);

  o.Repair = false;
  const av::MeshingPipelineResult none = av::RunMeshingPipeline(m, e, s, o);
  AV_CHECK(none.Repaired.Rounds == 0 && none.Repaired.NumInserted == 0);
  AV_CHECK(none.Repaired.Delaunay.NumInverted == none.Repaired.InitialInverted);
  AV_CHECK(none.Repaired.InitialInverted > 0);
  AV_CHECK(none.Repaired.Sites.Coords == s.Coords);
}

// Random sites in a cube make slivers; with sliver pushes only (no ODT), the fixed sites keep
// their exact values through every round while other sites of slivers move.
void TestFixedSites()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const av::SimplexMesh m = KuhnGrid(9, 9, 9, lo, hi);
  const av::Embedding e = MakeEmbedding(m, 5, SmoothExtra3);
  const av::SiteSet s = RandomSites(m, e, 150, 3);
  std::vector<std::uint8_t> fixed(s.NumSites(), 0);
  for (std::size_t i = 0; i < fixed.size(); i += 2)
    fixed[i] = 1;
  av::MeshingPipelineOptions o;
  o.ImproveRounds = 3;
  o.OdtIterations = 0;
  o.FixedSites = &fixed;
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(m, e, s, o);
  std::cout << "fixed sites: " << r.NumSlivers << " slivers, moved " << r.NumMovedSites << " in "
            << r.ImproveRoundsDone << " round(s)" << std::endl;
  AV_CHECK(r.NumSlivers > 0 && r.NumMovedSites > 0 && r.ImproveRoundsDone >= 1);
  AV_CHECK(r.NumOdtMovedSites == 0);
  CheckMoved(s, r);
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (fixed[i])
      AV_CHECK(!r.Moved[i] && SameSite(s, r.Repaired.Sites, i));

  // Without the flags the same sites are free: some of the formerly fixed ones move.
  o.FixedSites = nullptr;
  const av::MeshingPipelineResult free = av::RunMeshingPipeline(m, e, s, o);
  std::size_t fixedMoved = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i)
    fixedMoved += fixed[i] && free.Moved[i] ? 1 : 0;
  AV_CHECK(fixedMoved > 0);
}

// Every step is reported in order; returning false at a step stops the run there.
void TestAbort()
{
  const auto& [m, e, s] = FoldedSquare(0.2, 12.0, 60, 1);
  av::MeshingPipelineOptions o;
  o.ImproveRounds = 2;
  std::vector<av::MeshingStep> steps;
  o.Progress = [&](av::MeshingStep step)
  {
    steps.push_back(step);
    return true;
  };
  const av::MeshingPipelineResult r = av::RunMeshingPipeline(m, e, s, o);
  AV_CHECK(!r.Aborted && r.ImproveRoundsDone == 2);
  const std::vector<av::MeshingStep> expected = { av::MeshingStep::Voronoi,
    av::MeshingStep::Delaunay,
    av::MeshingStep::ImprovementRound,
    av::MeshingStep::ImprovementRound,
    av::MeshingStep::Improvement };
  AV_CHECK(steps == expected);
  AV_CHECK(r.Repaired.Sites.NumSites() >= s.NumSites());

  for (std::size_t stop = 0; stop < expected.size(); ++stop)
  {
    std::size_t calls = 0;
    o.Progress = [&](av::MeshingStep) { return ++calls <= stop; };
    const av::MeshingPipelineResult a = av::RunMeshingPipeline(m, e, s, o);
    AV_CHECK(a.Aborted && calls == stop + 1);
    AV_CHECK(a.Repaired.Sites.NumSites() == 0); // the repair never ran
  }
}

void TestBadInput()
{
  const av::SimplexMesh m = TriGrid(6, 6, 0, 0, 1, 1);
  const av::Embedding e = MakeEmbedding(m, 3, SmoothExtra);
  const av::SiteSet s = RandomSites(m, e, 12, 24);
  av::MeshingPipelineOptions o;
  o.ImproveRounds = -1;
  AV_CHECK_THROWS(av::RunMeshingPipeline(m, e, s, o));
  o = av::MeshingPipelineOptions();
  o.MaxRepairRounds = -1;
  AV_CHECK_THROWS(av::RunMeshingPipeline(m, e, s, o));
  o = av::MeshingPipelineOptions();
  const std::vector<std::uint8_t> tooFew(3, 0);
  o.FixedSites = &tooFew;
  AV_CHECK_THROWS(av::RunMeshingPipeline(m, e, s, o));
  av::SiteSet none;
  none.Dim = 3;
  AV_CHECK_THROWS(av::RunMeshingPipeline(m, e, none));
}
} // namespace

int TestMeshingPipeline(int, char*[])
{
  TestFolded();
  TestPaperPipeline();
  TestMeshImprovementStep();
  TestFixedSites();
  TestAbort();
  TestBadInput();
  return AV_TEST_RESULT();
}
