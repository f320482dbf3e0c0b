// SPDX-License-Identifier: BSD-3-Clause
// The iterative global step (CG + BoomerAMG): agreement with the direct solver, monotone energy
// even with a loose CG tolerance, and the run-to-convergence stopping rule.
#include "AnalyticMetrics.h"
#include "AnisoTestChecks.h"
#include "EdgeLengthError.h"
#include "EmbeddingSolver.h"
#include "IterativeGlobalSolver.h"
#include "StructuredMeshes.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
using namespace av;

/// The solver's properties from the smooth start (the aligned start adds a solve of its own and
/// starts near the optimum on these cube1 grids).
EmbeddingOptions SmoothStart()
{
  EmbeddingOptions o;
  o.Initialization = EmbeddingInitialization::Smooth;
  return o;
}

const double kLo[3] = { 0, 0, 0 }, kHi[3] = { 1, 1, 1 };

bool Monotone(const EmbeddingResult& r)
{
  for (std::size_t i = 1; i < r.EnergyHistory.size(); ++i)
  {
    if (r.EnergyHistory[i].Total > r.EnergyHistory[i - 1].Total)
    {
      std::cerr << "energy rose at iteration " << i << ": " << r.EnergyHistory[i - 1].Total
                << " -> " << r.EnergyHistory[i].Total << "\n";
      return false;
    }
  }
  return true;
}

/// Largest |a - b| over the free coordinates, relative to the largest |b|.
double RelativeDifference(const Embedding& a, const Embedding& b)
{
  double diff = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < b.Coords.size(); ++k)
  {
    diff = std::max(diff, std::abs(a.Coords[k] - b.Coords[k]));
    scale = std::max(scale, std::abs(b.Coords[k]));
  }
  return diff / scale;
}

/// Plain local/global steps in double: the direct and a tight iterative solve give the same
/// iterates (the steps are deterministic functions of the previous iterate).
void CheckAgreesWithDirect(const SimplexMesh& cube, const MetricField& metric)
{
  EmbeddingOptions o = SmoothStart();
  o.Iterations = 10;
  o.MaxIterations = 0;
  o.AndersonWindow = 0;
  o.SinglePrecisionSolve = false;
  o.GlobalSolver = EmbeddingGlobalSolver::Direct;
  const EmbeddingResult direct = ComputeEmbedding(cube, metric, o);
  o.GlobalSolver = EmbeddingGlobalSolver::Iterative;
  o.IterativeTolerance = 1e-10;
  // Both AMG matrices (the whole K, or its element-adjacent part with the regularizer's
  // two-ring on the diagonal) must give K's solution: only the CG iteration count may differ.
  for (const bool sparse : { false, true })
  {
    o.SparsePreconditioner = sparse;
    const EmbeddingResult iterative = ComputeEmbedding(cube, metric, o);
    AV_CHECK(!direct.IterativeSolve && iterative.IterativeSolve);
    AV_CHECK(iterative.IterationsDone == 10 && direct.IterationsDone == 10);
    AV_CHECK(iterative.SolverSolves == 50); // 10 steps x 5 free dimensions
    const double perSolve =
      static_cast<double>(iterative.SolverIterations) / iterative.SolverSolves;
    std::cout << (sparse ? "element-adjacent" : "full") << " AMG matrix: CG iterations per solve "
              << "at 1e-10: " << perSolve << " (max " << iterative.SolverMaxIterations << ")\n";
    AV_CHECK(perSolve > 0.0 && perSolve < 60.0); // AMG keeps CG short (measured about 10)
    const double d = RelativeDifference(iterative.Embedded, direct.Embedded);
    const double de =
      std::abs(iterative.EnergyHistory.back().Total - direct.EnergyHistory.back().Total) /
      direct.EnergyHistory.back().Total;
    std::cout << "iterative vs direct after 10 plain steps: coordinates " << d << ", energy " << de
              << "\n";
    AV_CHECK(d < 1e-6);
    AV_CHECK(de < 1e-8);
  }
  o.SparsePreconditioner = true;
  // A loose tolerance is visibly different: the comparison above can fail.
  o.IterativeTolerance = 1e-2;
  const EmbeddingResult loose = ComputeEmbedding(cube, metric, o);
  std::cout << "iterative at 1e-2 vs direct: coordinates "
            << RelativeDifference(loose.Embedded, direct.Embedded) << "\n";
  AV_CHECK(RelativeDifference(loose.Embedded, direct.Embedded) > 1e-6);
}

/// With Anderson and a very loose CG tolerance the energy still never rises: CG warm-started
/// from the current iterate cannot raise the quadratic energy, the local step only lowers it.
void CheckMonotone(const SimplexMesh& cube, const MetricField& metric)
{
  for (const double tol : { 1e-1, 1e-6 })
  {
    EmbeddingOptions o = SmoothStart();
    o.Iterations = 40;
    o.MaxIterations = 0;
    o.GlobalSolver = EmbeddingGlobalSolver::Iterative;
    o.IterativeTolerance = tol;
    const EmbeddingResult r = ComputeEmbedding(cube, metric, o);
    AV_CHECK(Monotone(r));
    AV_CHECK(r.DoublePrecisionRetries == 0); // never needed the accurate redo
    AV_CHECK(r.EnergyHistory.back().Total < 0.2 * r.EnergyHistory.front().Total);
    std::cout << "iterative, CG tolerance " << tol << ": E " << r.EnergyHistory.front().Total
              << " -> " << r.EnergyHistory.back().Total << ", "
              << static_cast<double>(r.SolverIterations) / r.SolverSolves
              << " CG iterations per solve\n";
  }
}

/// Mean relative decrease per iteration over the kConvergenceWindow iterations ending at `end`.
double WindowDecrease(const EmbeddingResult& r, std::size_t end)
{
  const double before = r.EnergyHistory[end - kConvergenceWindow].Total;
  return (before - r.EnergyHistory[end].Total) / (kConvergenceWindow * before);
}

/// Run to convergence: stops at the first iteration past Iterations whose windowed decrease is
/// below the tolerance, and not before.
void CheckConvergenceStop(const SimplexMesh& cube, const MetricField& metric)
{
  EmbeddingOptions o = SmoothStart();
  o.Iterations = 12;
  o.MaxIterations = 3000;
  o.ConvergenceTolerance = 1e-3;
  o.TargetAverageErrorPercent = 0.0; // the energy test alone
  const EmbeddingResult r = ComputeEmbedding(cube, metric, o);
  const std::size_t last = r.EnergyHistory.size() - 1;
  std::cout << "run to convergence (tolerance 1e-3): " << r.IterationsDone
            << " iterations, final decrease " << r.FinalRelativeDecrease << "\n";
  AV_CHECK(r.Converged);
  AV_CHECK(r.IterationsDone >= 12 && r.IterationsDone < 3000);
  AV_CHECK(static_cast<int>(last) == r.IterationsDone);
  AV_CHECK(WindowDecrease(r, last) <= o.ConvergenceTolerance);
  AV_CHECK(std::abs(WindowDecrease(r, last) - r.FinalRelativeDecrease) < 1e-15);
  for (std::size_t it = 12; it < last; ++it)
  {
    AV_CHECK(WindowDecrease(r, it) > o.ConvergenceTolerance); // it did not stop too late
  }
  // A tighter tolerance runs longer and ends lower.
  o.ConvergenceTolerance = 1e-4;
  const EmbeddingResult tighter = ComputeEmbedding(cube, metric, o);
  AV_CHECK(tighter.IterationsDone > r.IterationsDone);
  AV_CHECK(tighter.EnergyHistory.back().Total < r.EnergyHistory.back().Total);
  // The cap wins over the tolerance; MaxIterations <= Iterations runs exactly Iterations.
  o.ConvergenceTolerance = 0.0;
  o.MaxIterations = 20;
  const EmbeddingResult capped = ComputeEmbedding(cube, metric, o);
  AV_CHECK(capped.IterationsDone == 20 && !capped.Converged);
  o.MaxIterations = 0;
  AV_CHECK(ComputeEmbedding(cube, metric, o).IterationsDone == 12);
}

/// The error target: past Iterations, the run stops at the first iteration whose L_avg is at or
/// below the target (checked here with an independent evaluator in the progress callback).
void CheckErrorTarget(const SimplexMesh& cube, const MetricField& metric)
{
  const EdgeLengthErrorEvaluator evaluator(cube, metric);
  std::vector<double> lavg(1, -1.0);
  EmbeddingOptions o = SmoothStart();
  o.Iterations = 5;
  o.MaxIterations = 400;
  o.ConvergenceTolerance = 0.0; // only the error target (and the cap) stop the run
  o.TargetAverageErrorPercent = 2.0;
  o.Progress = [&](const EmbeddingProgress& p)
  {
    lavg.push_back(evaluator.Evaluate(p.Solver->CurrentEmbedding()).AveragePercent);
    return true;
  };
  const EmbeddingResult r = ComputeEmbedding(cube, metric, o);
  const int n = r.IterationsDone;
  std::cout << "error target 2 %: stopped at iteration " << n << " with L_avg "
            << r.FinalAverageErrorPercent << " % (at iteration 5: " << lavg[5] << " %)\n";
  AV_CHECK(lavg[5] > 2.0); // the fixed count alone does not reach it on this grid
  AV_CHECK(r.ReachedErrorTarget && r.Converged && n > 5 && n < 400);
  AV_CHECK(static_cast<int>(lavg.size()) == n + 1);
  AV_CHECK_NEAR(r.FinalAverageErrorPercent, lavg[n], 1e-12);
  AV_CHECK(lavg[n] <= 2.0);
  for (int it = 5; it < n; ++it)
  {
    AV_CHECK(lavg[it] > 2.0); // it stopped at the first one
  }
}

void CheckBadOptions(const SimplexMesh& cube, const MetricField& metric)
{
  EmbeddingOptions o = SmoothStart();
  o.Iterations = 1;
  o.GlobalSolver = EmbeddingGlobalSolver::Iterative;
  o.IterativeTolerance = 0.0;
  AV_CHECK_THROWS(ComputeEmbedding(cube, metric, o));
  o.IterativeTolerance = 1e-6;
  o.MaxIterations = -1;
  AV_CHECK_THROWS(ComputeEmbedding(cube, metric, o));
  o.MaxIterations = 0;
  o.ConvergenceTolerance = -1.0;
  AV_CHECK_THROWS(ComputeEmbedding(cube, metric, o));
}
/// The solver on its own, with a preconditioner matrix P != K: a 1D Laplacian K (tridiagonal)
/// and P = K + I. CG must return K's solution, not P's; a P of the wrong size is refused.
void CheckSeparatePreconditioner()
{
  const int n = 200;
  std::vector<Eigen::Triplet<double>> k, p;
  for (int i = 0; i < n; ++i)
  {
    k.emplace_back(i, i, 2.0);
    p.emplace_back(i, i, 3.0);
    if (i + 1 < n)
    {
      k.emplace_back(i + 1, i, -1.0);
      p.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> kl(n, n), pl(n, n);
  kl.setFromTriplets(k.begin(), k.end());
  pl.setFromTriplets(p.begin(), p.end());
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, 1);
  for (int i = 0; i < n; ++i)
  {
    x(i, 0) = std::sin(0.1 * i) + 0.01 * i;
  }
  const Eigen::SparseMatrix<double> full = kl.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd b = full * x;
  Eigen::MatrixXd sol = Eigen::MatrixXd::Zero(n, 1);
  IterativeGlobalSolver solver(kl, 1000, &pl);
  solver.Solve(b, sol, 1e-12);
  const double err = (sol - x).norm() / x.norm();
  std::cout << "K x = b with AMG on K + I: relative error " << err << ", "
            << solver.Statistics().Iterations << " CG iterations\n";
  AV_CHECK(err < 1e-8);
  AV_CHECK(solver.Statistics().NotConverged == 0);
  const Eigen::SparseMatrix<double> wrong(n - 1, n - 1);
  AV_CHECK_THROWS(IterativeGlobalSolver(kl, 10, &wrong));
}
/// Automatic with slow CG: the first step's CG is cut short, the step is solved again with the
/// factor and the run goes on direct, so it equals a direct run; with fast CG it stays iterative.
void CheckSwitchToDirect(const SimplexMesh& cube, const MetricField& metric)
{
  EmbeddingOptions o = SmoothStart();
  o.Iterations = 10;
  o.MaxIterations = 0;
  o.GlobalSolver = EmbeddingGlobalSolver::Direct;
  const EmbeddingResult direct = ComputeEmbedding(cube, metric, o);
  o.GlobalSolver = EmbeddingGlobalSolver::Automatic;
  o.IterativeMinVertices = 1;       // try the iterative solver on this small grid
  o.DirectSwitchCgIterations = 0.5; // any CG solve is "slow"
  const EmbeddingResult switched = ComputeEmbedding(cube, metric, o);
  AV_CHECK(switched.SwitchedToDirect && !switched.IterativeSolve);
  AV_CHECK(switched.SolverSolves == 5); // only the first step's 5 solves were iterative
  AV_CHECK(switched.FactorNonZeros == direct.FactorNonZeros && switched.FactorNonZeros > 0);
  const double d = RelativeDifference(switched.Embedded, direct.Embedded);
  std::cout << "switched to direct vs direct: coordinates " << d << "\n";
  AV_CHECK(d < 1e-12);
  o.DirectSwitchCgIterations = 1000.0; // CG converges: no switch
  const EmbeddingResult stays = ComputeEmbedding(cube, metric, o);
  AV_CHECK(stays.IterativeSolve && !stays.SwitchedToDirect && stays.SolverSolves == 50);
  o.DirectSwitchCgIterations = 0.0; // never
  const EmbeddingResult never = ComputeEmbedding(cube, metric, o);
  AV_CHECK(never.IterativeSolve && !never.SwitchedToDirect);
}
} // namespace

int TestIterativeGlobalSolver(int, char*[])
{
  const SimplexMesh cube = MakeKuhnTetGrid(13, 7, 7, kLo, kHi);
  const MetricField metric = EvaluateAnalyticMetric(AnalyticPreset::Cube1, cube);
  CheckSeparatePreconditioner();
  CheckAgreesWithDirect(cube, metric);
  CheckSwitchToDirect(cube, metric);
  CheckMonotone(cube, metric);
  CheckConvergenceStop(cube, metric);
  CheckErrorTarget(cube, metric);
  CheckBadOptions(cube, metric);
  return AV_TEST_RESULT();
}
