// SPDX-License-Identifier: BSD-3-Clause
// EmbeddingSolver: the high-dimensional embedding of a Riemannian metric (paper §3, Alg. 1).
#ifndef av_EmbeddingSolver_h
#define av_EmbeddingSolver_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace av
{

/// How the free coordinates (dimensions m+1..TargetDim) start.
enum class EmbeddingInitialization
{
  /// A smooth, low-frequency random field (a few random plane waves with wavelength of the
  /// order of the domain size) per free dimension: leaves the flat saddle in a coherent direction.
  Smooth,
  /// The paper's i.i.d. small random perturbation of every vertex.
  Random,
  /// The default. The first m free dimensions start as the least-squares fit (one global solve
  /// with the same matrix) of the targets Q (M_j - I)^{1/2}, Q the first m free axes: with the
  /// fixed input rows, T^T T = I + (M_j - I) = M_j wherever the fit is exact, so a metric whose
  /// stretch directions do not turn (boundary layers, Cube1/2) starts almost isometric. The
  /// other free dimensions keep the Smooth field. When the fit leaves more than
  /// AlignedStartMaxResidual of the targets' norm (directions that turn: stress fields, the
  /// spheres), or there are fewer free dimensions than m, or on surfaces, the Smooth start is
  /// kept, so those inputs embed exactly as with Smooth.
  MetricAligned
};

/// The constant metric M_j each element is fitted to (the paper: "constant per element").
enum class EmbeddingElementMetric
{
  /// The average of the element's vertex metrics (paper-notes.md). The default: the final
  /// meshes are better on every real case measured (Filters/Embedding/README.md).
  VertexMean,
  /// The metric whose lengths of the element's edges are the §5.1 lengths
  /// ℓ(a, b) = |(A_a + A_b) / 2 (b − a)| (their Gram matrix, by polarization). Neighbours then
  /// agree on the length of every shared edge, where vertex means of different vertex sets
  /// disagree by the metric's variation across an element. Elements whose edge lengths are far
  /// from any such metric (not a Euclidean simplex, or 4x from the mean) blend towards the mean.
  /// Lower L_avg on every preset and real volume measured, but worse final meshes: each element
  /// fitted alone makes the metric jump across faces, and the embedded volume bends there
  /// (rotor: 885 inverted dual tets before the repair against 4, G_avg 0.705 against 0.856).
  EdgeLengths
};

/// The three energies of Eq. 15 at one iterate (E_em with the optimal rotations for that iterate).
struct EmbeddingEnergy
{
  double Embedding = 0.0;      ///< E_em, Eq. 11 (weighted if ElementMeasureWeighting)
  double Regularization = 0.0; ///< E_reg (quadratic reading; / ℓ² with ScaleFreeRegularizer)
  double Total = 0.0;          ///< E_em + Mu * E_reg
};

/// How the global step's linear systems are solved.
enum class EmbeddingGlobalSolver
{
  /// Direct below IterativeSolverMinVertices() mesh vertices (20,000 for tet meshes, 150,000 for
  /// triangle meshes), iterative from there on, unless CG converges slowly on the mesh (more than
  /// kDirectSwitchCgIterations per solve in the first global step, up to kDirectSwitchMaxVertices
  /// vertices, the factor fitting in memory): then direct from the second step on.
  Automatic,
  /// Sparse Cholesky (CHOLMOD supernodal), factorised once; memory grows like n^1.3.
  Direct,
  /// Conjugate gradients preconditioned with algebraic multigrid (hierarchy from hypre's
  /// BoomerAMG, our threaded Chebyshev V-cycle), warm-started from the current iterate; memory
  /// linear in n.
  Iterative
};

/// Mesh sizes (vertices) from which EmbeddingGlobalSolver::Automatic picks the iterative solver,
/// measured (Filters/Embedding/README.md): on tet meshes the iterative solver is faster from
/// about 15k vertices (cube1) and never uses more memory; on triangle meshes the Cholesky fill
/// stays small and the direct solver is 1.7x faster at 26k vertices (cyclide2), so the switch
/// there is by memory.
constexpr std::size_t kIterativeSolverMinTetVertices = 20000;
constexpr std::size_t kIterativeSolverMinVertices = 150000;
/// The switch of EmbeddingGlobalSolver::Automatic for meshes of simplexDim-simplices.
inline std::size_t IterativeSolverMinVertices(int simplexDim)
{
  return simplexDim == 3 ? kIterativeSolverMinTetVertices : kIterativeSolverMinVertices;
}
/// Automatic: when the first global step's CG solves (capped at twice this) take more than this
/// many iterations on average, the solver factors the matrix and goes on direct. On grids the
/// first step takes about 3 (cube2); on squareBend 12, where both solvers cost the same; on meshes
/// adapted to an anisotropic metric 17 to over 300, where the direct solver was 2-17x faster
/// (hueeber1, 26k vertices: 2.5 s against 4.9 s; compressor at 10,000 sites, 84.6k vertices:
/// 18.5 s against 323 s).
constexpr double kDirectSwitchCgIterations = 15.0;
/// ... and only meshes up to this many vertices switch (the factor's time grows like n^1.5: at
/// 343k vertices the factorization alone took 67 s); the memory check of the factor still applies.
constexpr std::size_t kDirectSwitchMaxVertices = 250000;

class EmbeddingSolver;

/// What the progress callback sees after every iteration.
struct EmbeddingProgress
{
  int Iteration = 0;  ///< 1-based index of the iteration just finished
  int Iterations = 0; ///< requested number of iterations
  EmbeddingEnergy Energy;
  const EmbeddingSolver* Solver = nullptr; ///< call Solver->CurrentEmbedding() for a snapshot
};

/// Parameters of the embedding (defaults are the paper's, except Initialization and Anderson).
struct EmbeddingOptions
{
  int TargetDim = 8;       ///< m-bar, in [AmbientDim + 1, 20]
  int Iterations = 50;     ///< local/global iterations always run (the paper's 50; >= 0)
  double Mu = 100.0;       ///< weight of the regularizer (>= 0)
  /// Measure the regularizer's Laplacians in units of the mesh's largest bounding-box extent ℓ
  /// (E_reg / ℓ²), so that Mu means the same for a part given in millimetres and in metres (the
  /// paper's μ = 100 was chosen on unit-sized inputs). false (default): E_reg in the input's own
  /// length unit, as printed in the paper, so a mesh 1000x larger is regularized 10^6x more
  /// strongly. Unit-sized inputs (extent 1) are the same either way. Off by default because the
  /// weaker regularization of large-unit inputs gives lower L_avg but worse final meshes on the
  /// coarse real volumes (Filters/Embedding/README.md, "Regularizer and length unit").
  bool ScaleFreeRegularizer = false;
  std::uint64_t Seed = 1;  ///< seed of the initial random field (runs are reproducible)
  /// Stop when (E_prev - E) / E_prev falls below this (0 = run all iterations).
  double RelativeEnergyTolerance = 0.0;
  /// Run to convergence: after Iterations, keep iterating while the §5.1 edge length error
  /// L_avg is above TargetAverageErrorPercent (0: no error target) and the energy still drops
  /// by more than ConvergenceTolerance per iteration on average over the last
  /// kConvergenceWindow iterations, up to MaxIterations in all (MaxIterations <= Iterations:
  /// exactly Iterations). Inputs that fit at Iterations (the presets) stop there unchanged.
  int MaxIterations = 500;
  double ConvergenceTolerance = 1e-4;
  double TargetAverageErrorPercent = 2.0;
  EmbeddingGlobalSolver GlobalSolver = EmbeddingGlobalSolver::Automatic;
  /// Automatic: mesh vertices from which the iterative solver is tried (0 =
  /// IterativeSolverMinVertices(simplex dimension)).
  std::size_t IterativeMinVertices = 0;
  /// Automatic: the mean CG iterations per solve of the first global step above which the
  /// solver switches to direct (kDirectSwitchCgIterations; 0 = never switch).
  double DirectSwitchCgIterations = kDirectSwitchCgIterations;
  /// Iterative solver: stop each CG solve at |r| <= IterativeTolerance |b| (warm start from the
  /// current iterate; CG never raises the energy whatever the tolerance, see README).
  double IterativeTolerance = 1e-4;
  /// Iterative solver: build the AMG hierarchy on the element-adjacent part of K (the two-ring
  /// entries of the regularizer moved onto the diagonal, which keeps it SPD and above K) instead
  /// of on K itself: a quarter of the entries, cheaper V-cycles; CG still solves K exactly.
  bool SparsePreconditioner = true;
  /// false: the paper's unweighted sum over elements (Eq. 11); true: weight each element by its
  /// measure relative to the mean element measure (better posed on graded meshes).
  bool ElementMeasureWeighting = false;
  EmbeddingElementMetric ElementMetric = EmbeddingElementMetric::VertexMean;
  EmbeddingInitialization Initialization = EmbeddingInitialization::MetricAligned;
  /// MetricAligned: the largest relative residual sum_j w_j |F_j - Q S_j|² / sum_j w_j |S_j|²
  /// (F_j the fitted free Jacobian, S_j = (M_j - I)^{1/2}) at which the aligned start is kept.
  /// Measured (Filters/Embedding/README.md, "Metric-aligned start"): boundary layers and
  /// Cube1/2 0.0001-0.0035, where it is much better; the real volumes 0.008-0.04, Cube3 0.07,
  /// the spheres 0.13-0.17, where it is level or worse (segmenttet L_avg 2.5 -> 5.1 %, more
  /// inverted dual tets on four of the seven real volumes; SphereCylindrical 0.46 -> 2.0 %).
  double AlignedStartMaxResidual = 0.005;
  /// Amplitude of the initial field relative to the largest bounding-box extent (<= 0: default,
  /// 0.2 for Smooth and 1e-3 for Random).
  double InitialAmplitude = 0.0;
  /// Anderson acceleration window (previous iterates used, 0 = plain local/global). The
  /// accelerated iterate is kept only when it lowers the energy, so the energy never increases.
  int AndersonWindow = 5;
  /// Global-step solves with a single-precision copy of the Cholesky factor, tree-parallel
  /// (FloatSupernodalSolver): the solves are memory-bound, so this halves their traffic and
  /// uses every core. A plain step whose energy would rise because of the float rounding is
  /// redone with the double factor, so the energy still never increases.
  bool SinglePrecisionSolve = true;
  /// Separate bodies of the mesh (parts with no shared point) end apart in R^m (SeparateBodies),
  /// so that each is sampled and meshed as its own domain; off: as they come out of the solve.
  bool SeparateBodies = true;
  /// Called after every iteration; return false to stop early (the result then has Aborted set).
  std::function<bool(const EmbeddingProgress&)> Progress;
};

/// Output of the solver.
struct EmbeddingResult
{
  Embedding Embedded; ///< NumPoints x TargetDim, first AmbientDim columns = input points exactly
  /// Energy of the initial state (index 0) and after each iteration; never increases.
  std::vector<EmbeddingEnergy> EnergyHistory;
  int IterationsDone = 0;
  int AndersonAccepted = 0; ///< iterations that kept the accelerated iterate
  int AndersonRejected = 0; ///< iterations that fell back to the plain step
  bool Aborted = false;     ///< the progress callback asked to stop
  double SetupSeconds = 0.0;     ///< validation, element operators, matrix assembly
  double FactorSeconds = 0.0;    ///< sparse Cholesky analyse + factorise, or the AMG setup
                                 ///< (+ the factorization of a switch to direct, which happens
                                 ///< during the iterations and is in IterationSeconds too)
  double IterationSeconds = 0.0; ///< all iterations
  double LocalStepSeconds = 0.0; ///< part of IterationSeconds in local steps (incl. energies)
  double SolveSeconds = 0.0;     ///< part of IterationSeconds in the global-step solves
  int DoublePrecisionRetries = 0; ///< plain steps redone in double (SinglePrecisionSolve)
  std::size_t FactorNonZeros = 0; ///< non-zeros of the Cholesky factor
  bool IterativeSolve = false;    ///< the global steps used the iterative solver
  /// Automatic: CG converged slowly in the first global step, the rest were direct.
  bool SwitchedToDirect = false;
  long long SolverSolves = 0;     ///< iterative: CG solves (one per free dimension and step)
  long long SolverIterations = 0; ///< iterative: CG iterations summed over all solves
  int SolverMaxIterations = 0;    ///< iterative: most CG iterations of one solve
  std::size_t NumBodies = 1;      ///< bodies of the mesh (moved apart with SeparateBodies)
  /// ElementMetric EdgeLengths: elements blended towards the vertex mean (edge lengths far from
  /// any metric).
  std::size_t ElementMetricFallbacks = 0;
  /// Average relative energy decrease per iteration over the last kConvergenceWindow iterations
  /// at exit (fewer when fewer were run): the convergence measure.
  double FinalRelativeDecrease = 0.0;
  bool Converged = false; ///< stopped past Iterations on the error target or the tolerance
  bool ReachedErrorTarget = false; ///< L_avg <= TargetAverageErrorPercent at exit
  /// L_avg (%) at exit when the error target was evaluated (past Iterations), else -1.
  double FinalAverageErrorPercent = -1.0;
  /// A global step could not lower the energy even solved accurately (the double factor, or a
  /// 1000x tighter CG tolerance): the iterate is a fixed point at the solver's precision, so the
  /// run stopped there (Converged).
  bool Stalled = false;
  bool AlignedStart = false; ///< MetricAligned: the aligned start was kept
  /// MetricAligned: the relative residual of its fit (-1 when not tried: surfaces, too few free
  /// dimensions, another Initialization).
  double AlignedStartResidual = -1.0;
};

/// Iterations over which the convergence test averages the relative energy decrease (Anderson's
/// rejected steps make single-iteration decreases noisy).
constexpr int kConvergenceWindow = 10;

/**
 * Computes the self-intersection free high-d embedding of a simplicial mesh equipped with a
 * per-vertex metric (paper Alg. 1): the first m coordinates stay the input coordinates; the
 * TargetDim - m free ones minimize E_total = sum_j w_j |T_j - V_j A_j|_F^2 + Mu E_reg by
 * local (polar decomposition per element) / global (one sparse Cholesky factorisation, one
 * multi-right-hand-side solve per iteration) steps.
 *
 * Supported inputs: 2D domains (AmbientDim 2, SimplexDim 2, SPD 2x2 metrics), volumes (3, 3,
 * SPD 3x3) and surfaces (3, 2, positive semi-definite, typically rank-2 tangent metrics).
 * Construction validates the input (throws InputError) and factorises the system; Run() iterates.
 */
class EmbeddingSolver
{
public:
  EmbeddingSolver(const SimplexMesh& mesh, const MetricField& metric, const EmbeddingOptions& options);
  ~EmbeddingSolver();
  EmbeddingSolver(const EmbeddingSolver&) = delete;
  EmbeddingSolver& operator=(const EmbeddingSolver&) = delete;

  /// Runs the iterations (once) and returns the result.
  EmbeddingResult Run();

  /// The current iterate (valid during the progress callback and after Run()).
  Embedding CurrentEmbedding() const;

  /// Energy of the current iterate.
  EmbeddingEnergy CurrentEnergy() const;

private:
  struct Internals;
  std::unique_ptr<Internals> P;
};

/// Convenience: EmbeddingSolver(mesh, metric, options).Run().
EmbeddingResult ComputeEmbedding(const SimplexMesh& mesh, const MetricField& metric,
  const EmbeddingOptions& options = EmbeddingOptions());

} // namespace av

#endif
