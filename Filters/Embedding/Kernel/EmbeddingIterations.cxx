// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver iterations (Alg. 1): global step, Anderson-accelerated or plain local/global
// steps with the energy safeguard, progress, stopping, and Run().
#include "EmbeddingSolverInternals.h"

#include "AndersonAcceleration.h"
#include "BodySeparation.h"
#include "Stopwatch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <string>
#include <algorithm>
#include <cmath>
#include <utility>

namespace av
{

void EmbeddingSolver::Internals::RequireSolved()
{
  // A failed cholmod_solve (out of memory) leaves Eigen's result unwritten: never use it.
  if (this->Chol.info() != Eigen::Success)
  {
    throw InputError("embedding: the CHOLMOD solve failed (status " +
      std::to_string(this->Chol.cholmod().status) + ", -2 is out of memory)");
  }
}

Eigen::MatrixXd EmbeddingSolver::Internals::GlobalStep(const Eigen::MatrixXd& current, bool probe)
{
  this->GatherRightHandSides();
  const Eigen::MatrixXd& rhs = this->LastRhs;
  const Stopwatch clock;
  Eigen::MatrixXd sol;
  if (this->Iterative)
  {
    sol = current; // warm start: CG from here cannot raise the energy
    // An Automatic choice probes CG's convergence on the first step with a short cap.
    probe = probe && this->SwitchK.rows() > 0;
    const int cap = this->Iterative->GetMaxIterations();
    if (probe)
      this->Iterative->SetMaxIterations(
        static_cast<int>(std::ceil(2.0 * this->Options.DirectSwitchCgIterations)));
    this->Iterative->Solve(rhs, sol, this->Options.IterativeTolerance);
    this->SolveSeconds += clock.Seconds();
    if (probe)
    {
      this->Iterative->SetMaxIterations(cap);
      this->MaybeSwitchToDirect(); // its time counts as factorization
    }
    if (this->Iterative)
      return sol;
    // Switched to direct: this step is solved again with the factor.
  }
  const Stopwatch direct;
  if (this->FloatSolver)
  {
    sol.resize(rhs.rows(), rhs.cols());
    this->FloatSolver->Solve(rhs.data(), sol.data(), static_cast<int>(rhs.cols()));
  }
  else
  {
    sol = this->Chol.solve(rhs);
    this->RequireSolved();
  }
  this->SolveSeconds += direct.Seconds();
  return sol;
}

void EmbeddingSolver::Internals::MaybeSwitchToDirect()
{
  if (this->SwitchK.rows() == 0)
    return;
  const IterativeSolveStatistics st = this->Iterative->Statistics();
  Eigen::SparseMatrix<double> kmat = std::move(this->SwitchK);
  this->SwitchK = Eigen::SparseMatrix<double>();
  // The probe's cap is 2x the bar: a solve that hit it did not converge.
  const bool slow = st.NotConverged > 0 ||
    static_cast<double>(st.Iterations) >
      this->Options.DirectSwitchCgIterations * static_cast<double>(st.Solves);
  if (st.Solves == 0 || !slow)
    return;
  const Stopwatch clock;
  const double iterativeSetup = this->FactorSeconds;
  try
  {
    this->UseNestedDissection();
    this->Chol.analyzePattern(kmat);
    const std::vector<double> values(kmat.valuePtr(), kmat.valuePtr() + kmat.nonZeros());
    this->Factor(kmat, values, 0.0);
  }
  catch (const InputError&)
  {
    return; // the factor does not fit (or fails): stay iterative
  }
  this->SwitchedStatistics = st;
  this->SwitchedToDirect = true;
  this->Iterative.reset();
  // Factor() set FactorSeconds to its own time; the iterative setup's share stays counted.
  this->FactorSeconds = iterativeSetup + clock.Seconds();
}

Eigen::MatrixXd EmbeddingSolver::Internals::RedoGlobalStepAccurately(const Eigen::MatrixXd& current)
{
  const Stopwatch clock;
  Eigen::MatrixXd sol;
  if (this->Iterative)
  {
    sol = current;
    this->Iterative->Solve(
      this->LastRhs, sol, std::max(1e-12, 1e-3 * this->Options.IterativeTolerance));
  }
  else
  {
    sol = this->Chol.solve(this->LastRhs);
    this->RequireSolved();
  }
  this->SolveSeconds += clock.Seconds();
  return sol;
}

Eigen::MatrixXd EmbeddingSolver::Internals::GetFree() const
{
  Eigen::MatrixXd xr(static_cast<Eigen::Index>(this->NR), this->F);
  for (std::size_t i = 0; i < this->NP; ++i)
  {
    if (this->Reduced[i] >= 0)
    {
      for (int d = 0; d < this->F; ++d)
      {
        xr(this->Reduced[i], d) = this->X[i * this->MB + this->M + d];
      }
    }
  }
  return xr;
}

void EmbeddingSolver::Internals::SetFree(const Eigen::MatrixXd& xr)
{
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NP, 4096),
    [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        if (this->Reduced[i] >= 0)
        {
          for (int d = 0; d < this->F; ++d)
          {
            this->X[i * this->MB + this->M + d] = xr(this->Reduced[i], d);
          }
        }
      }
    });
}

bool EmbeddingSolver::Internals::TryAndersonStep(AndersonAcceleration& anderson,
  const Eigen::MatrixXd& g, Eigen::MatrixXd& x, Eigen::MatrixXd& xa, EmbeddingEnergy& cur,
  EmbeddingResult& res)
{
  if (!anderson.Extrapolate(x, g, xa))
  {
    return false;
  }
  this->SetFree(xa);
  const EmbeddingEnergy ea = this->LocalStep();
  if (ea.Total < cur.Total)
  {
    cur = ea;
    std::swap(x, xa);
    ++res.AndersonAccepted;
    return true;
  }
  ++res.AndersonRejected;
  return false;
}

void EmbeddingSolver::Internals::PlainStep(
  Eigen::MatrixXd& g, Eigen::MatrixXd& x, EmbeddingEnergy& cur, EmbeddingResult& res)
{
  this->SetFree(g);
  EmbeddingEnergy eg = this->LocalStep();
  if ((this->FloatSolver || this->Iterative) && eg.Total > cur.Total)
  {
    // The exact global step cannot raise the energy; the inexact one did: redo it accurately.
    g = this->RedoGlobalStepAccurately(x);
    this->SetFree(g);
    eg = this->LocalStep();
    ++res.DoublePrecisionRetries;
    if (eg.Total > cur.Total)
    {
      // Round-off level (CG's, or the double factor's on an ill-conditioned K such as a
      // boundary layer's): no step at all. The iterate is then a fixed point of every later
      // iteration too (same local step, same solve), so the run stops here as converged.
      this->SetFree(x);
      cur = this->LocalStep();
      this->Stalled = true;
      return;
    }
  }
  cur = eg;
  x = std::move(g);
}

bool EmbeddingSolver::Internals::ReportProgress(
  const EmbeddingSolver* solver, int iteration, const EmbeddingEnergy& cur) const
{
  if (!this->Options.Progress)
  {
    return true;
  }
  EmbeddingProgress pr;
  pr.Iteration = iteration;
  pr.Iterations = std::max(this->Options.Iterations, iteration); // more when run to convergence
  pr.Energy = cur;
  pr.Solver = solver;
  return this->Options.Progress(pr);
}

bool EmbeddingSolver::Internals::Converged(const std::vector<EmbeddingEnergy>& history) const
{
  const double tol = this->Options.RelativeEnergyTolerance;
  const double prev = history[history.size() - 2].Total;
  return tol > 0.0 && prev > 0.0 && (prev - history.back().Total) / prev < tol;
}

bool EmbeddingSolver::Internals::ShouldStop(
  int it, const std::vector<EmbeddingEnergy>& history, EmbeddingResult& res) const
{
  const EmbeddingOptions& o = this->Options;
  const int window = std::min<int>(kConvergenceWindow, static_cast<int>(history.size()) - 1);
  const double now = history.back().Total;
  const double before = history[history.size() - 1 - static_cast<std::size_t>(window)].Total;
  res.FinalRelativeDecrease = (before > 0.0 && window > 0) ? (before - now) / (window * before) : 0.0;
  if (this->Stalled)
  {
    res.Stalled = res.Converged = true;
    return true;
  }
  if (this->Converged(history))
  {
    return true;
  }
  if (it < o.Iterations)
  {
    return false;
  }
  // Past the fixed count: go on only while the error is above the target and the energy still
  // drops (averaged over the window).
  if (this->ErrorTarget)
  {
    Embedding current;
    current.Dim = this->MB;
    current.Coords = this->X;
    res.FinalAverageErrorPercent = this->ErrorTarget->Evaluate(current).AveragePercent;
    if (res.FinalAverageErrorPercent <= o.TargetAverageErrorPercent)
    {
      res.ReachedErrorTarget = res.Converged = true;
      return true;
    }
  }
  const bool converged = window >= kConvergenceWindow &&
    res.FinalRelativeDecrease <= o.ConvergenceTolerance;
  res.Converged = converged;
  return converged || it >= std::max(o.Iterations, o.MaxIterations);
}

void EmbeddingSolver::Internals::TryMetricAlignedStart(EmbeddingResult& res)
{
  if (this->Options.Initialization != EmbeddingInitialization::MetricAligned || this->K != this->M ||
    this->F < this->M)
  {
    return;
  }
  const Eigen::MatrixXd smooth = this->GetFree();
  // The eigen frame first (exact where the stretch direction is a gradient direction, turning or
  // not), then the symmetric root (exact where the frame is constant); the better fit is kept.
  Eigen::MatrixXd best;
  double bestResidual = -1.0;
  for (const bool eigenFrame : { true, false })
  {
    this->BuildAlignedTargets(eigenFrame);
    this->SeedMetricAlignedRightHandSides();
    // Not the solver probe: this solve starts far from its solution (the smooth field), so its
    // CG count says little about the iterations' warm-started solves.
    Eigen::MatrixXd aligned = this->GlobalStep(smooth, false);
    // The free dimensions past the first m keep their smooth field: room to bend.
    aligned.rightCols(this->F - this->M) = smooth.rightCols(this->F - this->M);
    this->SetFree(aligned);
    const double residual = this->MetricAlignedResidual();
    if (bestResidual < 0.0 || residual < bestResidual)
    {
      bestResidual = residual;
      best = std::move(aligned);
    }
    if (bestResidual <= this->Options.AlignedStartMaxResidual)
      break;
  }
  this->AlignedTarget = std::vector<Eigen::Matrix3d>();
  this->AlignedFrames = std::vector<Eigen::Matrix3d>();
  this->AlignedRoots = std::vector<Eigen::Vector3d>();
  res.AlignedStartResidual = bestResidual;
  res.AlignedStart = bestResidual <= this->Options.AlignedStartMaxResidual;
  this->SetFree(res.AlignedStart ? best : smooth);
}

EmbeddingResult EmbeddingSolver::Run()
{
  Internals& p = *this->P;
  if (p.Ran)
  {
    throw InputError("embedding: EmbeddingSolver::Run() may be called only once");
  }
  p.Ran = true;
  EmbeddingResult res;
  res.SetupSeconds = p.SetupSeconds;
  res.FactorSeconds = p.FactorSeconds;
  res.FactorNonZeros = p.FactorNonZeros;
  const Stopwatch clock;

  p.TryMetricAlignedStart(res);
  EmbeddingEnergy cur = p.LocalStep();
  res.EnergyHistory.push_back(cur);
  Eigen::MatrixXd x = p.GetFree();

  // Anderson acceleration (type II) on the fixed-point map x -> G(x) = global(local(x)), with the
  // energy safeguard of Peng et al. 2018: keep the accelerated iterate only if it lowers E_total,
  // else take the plain step (whose energy is never higher).
  AndersonAcceleration anderson(p.Options.AndersonWindow);
  Eigen::MatrixXd xa;
  const int cap = std::max(p.Options.Iterations, p.Options.MaxIterations);
  for (int it = 1; it <= cap; ++it)
  {
    Eigen::MatrixXd g = p.GlobalStep(x);
    if (!p.TryAndersonStep(anderson, g, x, xa, cur, res))
    {
      p.PlainStep(g, x, cur, res);
    }
    res.EnergyHistory.push_back(cur);
    res.IterationsDone = it;
    if (!p.ReportProgress(this, it, cur))
    {
      res.Aborted = true;
      break;
    }
    if (p.ShouldStop(it, res.EnergyHistory, res))
    {
      break;
    }
  }
  res.IterationSeconds = clock.Seconds();
  // A switch to direct factored during the iterations (also counted in IterationSeconds).
  res.FactorSeconds = p.FactorSeconds;
  res.FactorNonZeros = p.FactorNonZeros;
  res.LocalStepSeconds = p.LocalSeconds;
  res.SolveSeconds = p.SolveSeconds;
  if (p.Iterative || p.SwitchedToDirect)
  {
    const IterativeSolveStatistics& st =
      p.Iterative ? p.Iterative->Statistics() : p.SwitchedStatistics;
    res.IterativeSolve = p.Iterative != nullptr;
    res.SwitchedToDirect = p.SwitchedToDirect;
    res.SolverSolves = st.Solves;
    res.SolverIterations = st.Iterations;
    res.SolverMaxIterations = st.MaxIterations;
  }
  res.Embedded = this->CurrentEmbedding();
  res.NumBodies = p.NumBodies;
  res.ElementMetricFallbacks = p.ElementMetricFallbacks;
  if (p.Options.SeparateBodies)
    SeparateBodies(p.PointBody, p.NumBodies, p.M, res.Embedded);
  return res;
}

} // namespace av
