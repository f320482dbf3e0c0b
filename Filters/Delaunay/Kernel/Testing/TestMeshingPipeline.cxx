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
  const av::MeshingPipelineOptions o;
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
  AV_CHECK(r.Repaired.Converged && r.Repaired.Delaunay.NumInverted == 0);
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
  TestFixedSites();
  TestAbort();
  TestBadInput();
  return AV_TEST_RESULT();
}
