// SPDX-License-Identifier: BSD-3-Clause
// IterativeGlobalSolver: hypre PCG + BoomerAMG on MPI_COMM_SELF (see the header).
#include "IterativeGlobalSolver.h"

#include "InputError.h"
#include "Stopwatch.h"

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include <algorithm>
#include <mutex>
#include <numeric>
#include <string>
#include <vector>

namespace av
{

namespace
{

/// hypre (Debian's build has MPI) needs MPI initialized. A process that did not do it (the CLI,
/// the benchmark, a plain Python session) gets a singleton MPI here, finalized at exit; inside
/// pvbatch/mpiexec the application's MPI is used as is.
class MpiForHypre
{
public:
  static void Ensure()
  {
    static MpiForHypre instance;
    (void)instance;
  }

private:
  MpiForHypre()
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized)
    {
      int provided = 0;
      // Serialized: hypre calls are guarded by HypreMutex(), from whichever thread runs them.
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
      this->Owned = true;
    }
    HYPRE_Init();
  }
  ~MpiForHypre()
  {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized)
    {
      HYPRE_Finalize();
      if (this->Owned)
      {
        MPI_Finalize();
      }
    }
  }
  bool Owned = false;
};

std::mutex& HypreMutex()
{
  static std::mutex m;
  return m;
}

void Check(HYPRE_Int code, const char* what)
{
  if (code != 0 && !HYPRE_CheckError(code, HYPRE_ERROR_CONV))
  {
    char message[256] = { 0 };
    HYPRE_DescribeError(code, message);
    HYPRE_ClearAllErrors();
    throw InputError(std::string("embedding: hypre failed in ") + what + ": " + message);
  }
  HYPRE_ClearAllErrors();
}

/// The V-cycle of a hierarchy built on P, fine level included (BoomerAMGSolve smooths the fine
/// level with the matrix it is given: PCG would give it K). PCG passes this through as its
/// opaque preconditioner data.
struct SeparatePreconditioner
{
  HYPRE_Solver Amg = nullptr;
  HYPRE_ParCSRMatrix P = nullptr;
};

} // namespace

struct IterativeGlobalSolver::Hypre
{
  HYPRE_IJMatrix Matrix = nullptr, Preconditioner = nullptr;
  HYPRE_IJVector B = nullptr, X = nullptr;
  HYPRE_ParCSRMatrix ParMatrix = nullptr, ParPreconditioner = nullptr;
  HYPRE_ParVector ParB = nullptr, ParX = nullptr;
  HYPRE_Solver Pcg = nullptr, Amg = nullptr;
  SeparatePreconditioner Separate;   // PCG's preconditioner data when P is given
  std::vector<HYPRE_BigInt> Indices; // 0..n-1, for the vector transfers
  bool SetUp = false;

  ~Hypre()
  {
    if (this->Pcg)
      HYPRE_ParCSRPCGDestroy(this->Pcg);
    if (this->Amg)
      HYPRE_BoomerAMGDestroy(this->Amg);
    if (this->B)
      HYPRE_IJVectorDestroy(this->B);
    if (this->X)
      HYPRE_IJVectorDestroy(this->X);
    if (this->Matrix)
      HYPRE_IJMatrixDestroy(this->Matrix);
    if (this->Preconditioner)
      HYPRE_IJMatrixDestroy(this->Preconditioner);
  }

  void BuildMatrix(const Eigen::SparseMatrix<double>& lower);
  void BuildVectors(HYPRE_Int n);
  void BuildSolver(int maxIterations);
};

namespace
{
/// The full symmetric matrix of a lower triangle as a hypre IJ/ParCSR matrix on MPI_COMM_SELF.
void BuildIJMatrix(const Eigen::SparseMatrix<double>& lower,
  const std::vector<HYPRE_BigInt>& indices,
  HYPRE_IJMatrix& matrix,
  HYPRE_ParCSRMatrix& par)
{
  // hypre wants CSR rows; we hold the lower triangle by columns: column c of the lower triangle
  // is the upper part of row c, and each of its off-diagonal entries (r, c) is also entry (c) of
  // row r.
  const HYPRE_Int n = static_cast<HYPRE_Int>(lower.rows());
  std::vector<HYPRE_Int> count(static_cast<std::size_t>(n), 0);
  for (Eigen::Index c = 0; c < lower.outerSize(); ++c)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it)
    {
      ++count[it.row()];
      if (it.row() != c)
      {
        ++count[c];
      }
    }
  }
  std::vector<std::size_t> start(static_cast<std::size_t>(n) + 1, 0);
  std::partial_sum(count.begin(), count.end(), start.begin() + 1);
  std::vector<HYPRE_BigInt> cols(start.back());
  std::vector<double> vals(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (Eigen::Index c = 0; c < lower.outerSize(); ++c)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it)
    {
      const std::size_t r = static_cast<std::size_t>(it.row());
      cols[fill[r]] = static_cast<HYPRE_BigInt>(c);
      vals[fill[r]++] = it.value();
      if (it.row() != c)
      {
        cols[fill[c]] = static_cast<HYPRE_BigInt>(r);
        vals[fill[c]++] = it.value();
      }
    }
  }
  Check(HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &matrix), "IJMatrixCreate");
  Check(HYPRE_IJMatrixSetObjectType(matrix, HYPRE_PARCSR), "IJMatrixSetObjectType");
  std::vector<HYPRE_Int> offd(static_cast<std::size_t>(n), 0);
  Check(HYPRE_IJMatrixSetDiagOffdSizes(matrix, count.data(), offd.data()), "SetDiagOffdSizes");
  Check(HYPRE_IJMatrixInitialize(matrix), "IJMatrixInitialize");
  Check(HYPRE_IJMatrixSetValues(matrix, n, count.data(), indices.data(), cols.data(), vals.data()),
    "IJMatrixSetValues");
  Check(HYPRE_IJMatrixAssemble(matrix), "IJMatrixAssemble");
  Check(HYPRE_IJMatrixGetObject(matrix, reinterpret_cast<void**>(&par)), "IJMatrixGetObject");
}

HYPRE_Int SeparatePreconditionerSolve(HYPRE_Solver data,
  HYPRE_Matrix,
  HYPRE_Vector b,
  HYPRE_Vector x)
{
  const SeparatePreconditioner* pc = reinterpret_cast<const SeparatePreconditioner*>(data);
  return HYPRE_BoomerAMGSolve(
    pc->Amg, pc->P, reinterpret_cast<HYPRE_ParVector>(b), reinterpret_cast<HYPRE_ParVector>(x));
}

/// PCG's preconditioner-setup hook when the hierarchy was built beforehand on P.
HYPRE_Int HierarchyAlreadyBuilt(HYPRE_Solver, HYPRE_Matrix, HYPRE_Vector, HYPRE_Vector)
{
  return 0;
}
} // namespace

void IterativeGlobalSolver::Hypre::BuildMatrix(const Eigen::SparseMatrix<double>& lower)
{
  const HYPRE_Int n = static_cast<HYPRE_Int>(lower.rows());
  this->Indices.resize(static_cast<std::size_t>(n));
  std::iota(this->Indices.begin(), this->Indices.end(), HYPRE_BigInt(0));
  BuildIJMatrix(lower, this->Indices, this->Matrix, this->ParMatrix);
  this->BuildVectors(n);
}

void IterativeGlobalSolver::Hypre::BuildVectors(HYPRE_Int n)
{
  for (HYPRE_IJVector* v : { &this->B, &this->X })
  {
    Check(HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, v), "IJVectorCreate");
    Check(HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR), "IJVectorSetObjectType");
    Check(HYPRE_IJVectorInitialize(*v), "IJVectorInitialize");
    Check(HYPRE_IJVectorAssemble(*v), "IJVectorAssemble");
  }
  Check(HYPRE_IJVectorGetObject(this->B, reinterpret_cast<void**>(&this->ParB)), "GetObject b");
  Check(HYPRE_IJVectorGetObject(this->X, reinterpret_cast<void**>(&this->ParX)), "GetObject x");
}

void IterativeGlobalSolver::Hypre::BuildSolver(int maxIterations)
{
  // BoomerAMG as a preconditioner: one V-cycle, no own stopping test. 3D elasticity-free scalar
  // problem: HMIS coarsening with extended+i interpolation truncated to 4 entries per row (the
  // usual low-complexity choice for 3D), strength 0.5 (hypre's advice for 3D), one level of
  // aggressive coarsening to keep the hierarchy's memory near that of the matrix, symmetric l1
  // Gauss-Seidel (relax type 8) so that the V-cycle is an SPD preconditioner for CG.
  Check(HYPRE_BoomerAMGCreate(&this->Amg), "BoomerAMGCreate");
  HYPRE_BoomerAMGSetPrintLevel(this->Amg, 0);
  HYPRE_BoomerAMGSetMaxIter(this->Amg, 1);
  HYPRE_BoomerAMGSetTol(this->Amg, 0.0);
  HYPRE_BoomerAMGSetCoarsenType(this->Amg, 10);
  HYPRE_BoomerAMGSetInterpType(this->Amg, 6);
  HYPRE_BoomerAMGSetPMaxElmts(this->Amg, 4);
  HYPRE_BoomerAMGSetStrongThreshold(this->Amg, 0.5);
  HYPRE_BoomerAMGSetAggNumLevels(this->Amg, 1);
  HYPRE_BoomerAMGSetRelaxType(this->Amg, 8);
  HYPRE_BoomerAMGSetNumSweeps(this->Amg, 1);
  Check(HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &this->Pcg), "PCGCreate");
  HYPRE_PCGSetMaxIter(this->Pcg, maxIterations);
  HYPRE_PCGSetTwoNorm(this->Pcg, 1);
  HYPRE_PCGSetPrintLevel(this->Pcg, 0);
  if (this->ParPreconditioner)
  {
    // The hierarchy of the sparser matrix P, built here; CG itself multiplies by K.
    Check(HYPRE_BoomerAMGSetup(this->Amg, this->ParPreconditioner, this->ParB, this->ParX),
      "BoomerAMGSetup");
    this->Separate.Amg = this->Amg;
    this->Separate.P = this->ParPreconditioner;
    HYPRE_PCGSetPrecond(this->Pcg,
      reinterpret_cast<HYPRE_PtrToSolverFcn>(SeparatePreconditionerSolve),
      reinterpret_cast<HYPRE_PtrToSolverFcn>(HierarchyAlreadyBuilt),
      reinterpret_cast<HYPRE_Solver>(&this->Separate));
  }
  else
  {
    HYPRE_PCGSetPrecond(this->Pcg,
      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup),
      this->Amg);
  }
  // The hierarchy depends on the matrix only: build it now (PCG setup calls AMG setup).
  Check(HYPRE_ParCSRPCGSetup(this->Pcg, this->ParMatrix, this->ParB, this->ParX), "PCGSetup");
  this->SetUp = true;
}

IterativeGlobalSolver::IterativeGlobalSolver(const Eigen::SparseMatrix<double>& lower,
  int maxIterations,
  const Eigen::SparseMatrix<double>* preconditionerLower)
  : H(new Hypre)
{
  const Stopwatch clock;
  if (lower.rows() != lower.cols() || lower.rows() == 0)
  {
    throw InputError("embedding: the iterative solver needs a non-empty square matrix");
  }
  if (preconditionerLower &&
    (preconditionerLower->rows() != lower.rows() || preconditionerLower->cols() != lower.cols()))
  {
    throw InputError("embedding: the preconditioner's matrix does not match the system's size");
  }
  MpiForHypre::Ensure();
  const std::lock_guard<std::mutex> lock(HypreMutex());
  this->H->BuildMatrix(lower);
  if (preconditionerLower)
  {
    BuildIJMatrix(
      *preconditionerLower, this->H->Indices, this->H->Preconditioner, this->H->ParPreconditioner);
  }
  this->H->BuildSolver(std::max(1, maxIterations));
  this->Stats.SetupSeconds = clock.Seconds();
}

IterativeGlobalSolver::~IterativeGlobalSolver()
{
  const std::lock_guard<std::mutex> lock(HypreMutex());
  this->H.reset();
}

long long IterativeGlobalSolver::Solve(const Eigen::MatrixXd& rhs,
  Eigen::MatrixXd& x,
  double tolerance)
{
  const std::lock_guard<std::mutex> lock(HypreMutex());
  Hypre& h = *this->H;
  const HYPRE_Int n = static_cast<HYPRE_Int>(h.Indices.size());
  HYPRE_PCGSetTol(h.Pcg, tolerance);
  long long total = 0;
  for (Eigen::Index d = 0; d < rhs.cols(); ++d)
  {
    Check(HYPRE_IJVectorSetValues(h.B, n, h.Indices.data(), rhs.col(d).data()), "set b");
    Check(HYPRE_IJVectorSetValues(h.X, n, h.Indices.data(), x.col(d).data()), "set x");
    // A zero right-hand side has the exact solution 0; hypre's relative test needs |b| > 0.
    if (rhs.col(d).squaredNorm() == 0.0)
    {
      x.col(d).setZero();
      continue;
    }
    Check(HYPRE_ParCSRPCGSolve(h.Pcg, h.ParMatrix, h.ParB, h.ParX), "PCGSolve");
    HYPRE_Int iterations = 0;
    double residual = 0.0;
    HYPRE_PCGGetNumIterations(h.Pcg, &iterations);
    HYPRE_PCGGetFinalRelativeResidualNorm(h.Pcg, &residual);
    Check(HYPRE_IJVectorGetValues(h.X, n, h.Indices.data(), x.col(d).data()), "get x");
    total += iterations;
    ++this->Stats.Solves;
    this->Stats.MaxIterations = std::max<int>(this->Stats.MaxIterations, iterations);
    this->Stats.WorstRelativeResidual = std::max(this->Stats.WorstRelativeResidual, residual);
    if (residual > tolerance)
    {
      ++this->Stats.NotConverged;
    }
  }
  this->Stats.Iterations += total;
  return total;
}

} // namespace av
