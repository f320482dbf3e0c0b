// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver: construction (validation, assembly and factorization, overlapped with the
// symbolic analysis), accessors and ComputeEmbedding. Run() is in EmbeddingIterations.cxx.
#include "EmbeddingSolver.h"

#include "EmbeddingSolverInternals.h"
#include "MeshTopology.h"
#include "Stopwatch.h"

#include <algorithm>
#include <thread>

namespace av
{

EmbeddingSolver::EmbeddingSolver(
  const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& options)
  : P(new Internals)
{
  const Stopwatch clock;
  Internals& p = *this->P;
  p.Options = options;
  p.Validate(mesh, metric);
  p.M = mesh.AmbientDim;
  p.K = mesh.SimplexDim;
  p.MB = options.TargetDim;
  p.F = p.MB - p.M;
  p.NP = mesh.NumPoints();
  p.NE = mesh.NumCells();
  p.Cells = mesh.Cells;
  if (options.ScaleFreeRegularizer)
  {
    const double ext = LargestExtent(mesh);
    p.RegularizerScale = ext > 0.0 ? 1.0 / (ext * ext) : 1.0;
  }
  p.BuildTopology(mesh);
  p.NumBodies = LabelBodies(mesh, p.PointBody);
  if (options.TargetAverageErrorPercent > 0.0 &&
    std::max(options.Iterations, options.MaxIterations) > options.Iterations)
  {
    p.ErrorMesh = mesh;
    p.ErrorTarget.reset(new EdgeLengthErrorEvaluator(p.ErrorMesh, metric));
  }
  const std::size_t iterativeFrom = options.IterativeMinVertices > 0
    ? options.IterativeMinVertices
    : IterativeSolverMinVertices(mesh.SimplexDim);
  const bool iterative = options.GlobalSolver == EmbeddingGlobalSolver::Iterative ||
    (options.GlobalSolver == EmbeddingGlobalSolver::Automatic && p.NP >= iterativeFrom);
  if (iterative)
  {
    Eigen::SparseMatrix<double> kmat;
    std::vector<double> values;
    p.AssembleLower(false, kmat, nullptr);
    p.BuildElements(mesh, metric);
    p.AssembleLower(true, kmat, &values);
    p.InitializeState(mesh);
    p.SetupIterative(kmat, values);
    if (options.GlobalSolver == EmbeddingGlobalSolver::Automatic &&
      options.DirectSwitchCgIterations > 0.0 && p.NP <= kDirectSwitchMaxVertices && p.Iterative)
    {
      p.SwitchK = kmat; // SetupIterative put the values in
    }
    p.SetupSeconds = clock.Seconds() - p.FactorSeconds;
    return;
  }
  // The fill-reducing ordering and symbolic analysis (single-threaded, ~0.7 s on cube2) need
  // only the pattern: they run on their own thread while the element operators, the values of
  // K and the initial state are computed.
  Eigen::SparseMatrix<double> kmat;
  p.AssembleLower(false, kmat, nullptr);
  // Nested dissection keeps the fill of the two-ring stencil (L^T L) well below AMD's
  // (cube2 101x21x21: 38.6M entries with NESDIS, 39.4M METIS, 47.7M AMD).
  p.UseNestedDissection();
  std::thread analyser([&p, &kmat]() { p.Chol.analyzePattern(kmat); });
  std::vector<double> values;
  try
  {
    p.BuildElements(mesh, metric);
    p.AssembleLower(true, kmat, &values);
    p.InitializeState(mesh);
  }
  catch (...)
  {
    analyser.join();
    throw;
  }
  const Stopwatch wait;
  analyser.join();
  p.Factor(kmat, values, wait.Seconds());
  // FactorSeconds: the factorization's share of the wall time (the analysis it waited for plus
  // the numeric factorization); the overlapped part of the analysis counts as setup.
  p.SetupSeconds = clock.Seconds() - p.FactorSeconds;
}

EmbeddingSolver::~EmbeddingSolver() = default;

Embedding EmbeddingSolver::CurrentEmbedding() const
{
  Embedding e;
  e.Dim = this->P->MB;
  e.Coords = this->P->X;
  return e;
}

EmbeddingEnergy EmbeddingSolver::CurrentEnergy() const
{
  return this->P->Energy;
}

EmbeddingResult ComputeEmbedding(
  const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& options)
{
  EmbeddingSolver solver(mesh, metric, options);
  return solver.Run();
}

} // namespace av
