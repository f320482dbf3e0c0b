// SPDX-License-Identifier: BSD-3-Clause
#include "BoomerAmgHierarchy.h"

#include "InputError.h"

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
// The AMG data structure (levels, interpolations): hypre's own internal header, shipped by
// libhypre-dev; it matches the library of the same package.
#include <_hypre_parcsr_ls.h>
#include <mpi.h>

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
  if (code != 0)
  {
    char message[256] = { 0 };
    HYPRE_DescribeError(code, message);
    HYPRE_ClearAllErrors();
    throw InputError(std::string("embedding: hypre failed in ") + what + ": " + message);
  }
}

/// Owns the hypre objects of one setup; destroyed before the mutex is released.
struct HypreSetup
{
  HYPRE_IJMatrix Matrix = nullptr;
  HYPRE_IJVector B = nullptr, X = nullptr;
  HYPRE_Solver Amg = nullptr;
  ~HypreSetup()
  {
    if (this->Amg)
      HYPRE_BoomerAMGDestroy(this->Amg);
    if (this->B)
      HYPRE_IJVectorDestroy(this->B);
    if (this->X)
      HYPRE_IJVectorDestroy(this->X);
    if (this->Matrix)
      HYPRE_IJMatrixDestroy(this->Matrix);
  }
};

/// The local (diag) block of a ParCSR matrix on one rank; its offd block must be empty.
CsrMatrix CopyLocal(hypre_ParCSRMatrix* m, const char* what)
{
  hypre_CSRMatrix* diag = hypre_ParCSRMatrixDiag(m);
  hypre_CSRMatrix* offd = hypre_ParCSRMatrixOffd(m);
  if (offd && hypre_CSRMatrixNumNonzeros(offd) != 0)
  {
    throw InputError(std::string("embedding: hypre's ") + what + " has off-rank entries");
  }
  const int rows = hypre_CSRMatrixNumRows(diag);
  const int cols = hypre_CSRMatrixNumCols(diag);
  const HYPRE_Int* i = hypre_CSRMatrixI(diag);
  const HYPRE_Int* j = hypre_CSRMatrixJ(diag);
  const HYPRE_Complex* v = hypre_CSRMatrixData(diag);
  std::vector<std::int64_t> start(static_cast<std::size_t>(rows) + 1);
  for (int r = 0; r <= rows; ++r)
  {
    start[r] = i[r];
  }
  const std::size_t nnz = static_cast<std::size_t>(start.back());
  return CsrMatrix(
    rows, cols, std::move(start), std::vector<int>(j, j + nnz), std::vector<double>(v, v + nnz));
}

} // namespace

AmgHierarchy BuildBoomerAmgHierarchy(const CsrMatrix& a)
{
  const HYPRE_Int n = a.Rows();
  if (n == 0 || a.Cols() != n)
  {
    throw InputError("embedding: the AMG hierarchy needs a non-empty square matrix");
  }
  MpiForHypre::Ensure();
  const std::lock_guard<std::mutex> lock(HypreMutex());
  HypreSetup h;
  std::vector<HYPRE_BigInt> rowsIndex(static_cast<std::size_t>(n));
  std::iota(rowsIndex.begin(), rowsIndex.end(), HYPRE_BigInt(0));
  std::vector<HYPRE_Int> count(static_cast<std::size_t>(n)), offd(static_cast<std::size_t>(n), 0);
  for (HYPRE_Int r = 0; r < n; ++r)
  {
    count[r] = static_cast<HYPRE_Int>(a.RowStart()[r + 1] - a.RowStart()[r]);
  }
  const std::vector<HYPRE_BigInt> cols(a.Column().begin(), a.Column().end());
  Check(HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &h.Matrix), "IJMatrixCreate");
  Check(HYPRE_IJMatrixSetObjectType(h.Matrix, HYPRE_PARCSR), "IJMatrixSetObjectType");
  Check(HYPRE_IJMatrixSetDiagOffdSizes(h.Matrix, count.data(), offd.data()), "SetDiagOffdSizes");
  Check(HYPRE_IJMatrixInitialize(h.Matrix), "IJMatrixInitialize");
  Check(HYPRE_IJMatrixSetValues(
          h.Matrix, n, count.data(), rowsIndex.data(), cols.data(), a.Value().data()),
    "IJMatrixSetValues");
  Check(HYPRE_IJMatrixAssemble(h.Matrix), "IJMatrixAssemble");
  HYPRE_ParCSRMatrix par = nullptr;
  Check(HYPRE_IJMatrixGetObject(h.Matrix, reinterpret_cast<void**>(&par)), "IJMatrixGetObject");
  HYPRE_ParVector parB = nullptr, parX = nullptr;
  for (HYPRE_IJVector* v : { &h.B, &h.X })
  {
    Check(HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, v), "IJVectorCreate");
    Check(HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR), "IJVectorSetObjectType");
    Check(HYPRE_IJVectorInitialize(*v), "IJVectorInitialize");
    Check(HYPRE_IJVectorAssemble(*v), "IJVectorAssemble");
  }
  Check(HYPRE_IJVectorGetObject(h.B, reinterpret_cast<void**>(&parB)), "GetObject b");
  Check(HYPRE_IJVectorGetObject(h.X, reinterpret_cast<void**>(&parX)), "GetObject x");

  Check(HYPRE_BoomerAMGCreate(&h.Amg), "BoomerAMGCreate");
  HYPRE_BoomerAMGSetPrintLevel(h.Amg, 0);
  HYPRE_BoomerAMGSetCoarsenType(h.Amg, 10);
  HYPRE_BoomerAMGSetInterpType(h.Amg, 6);
  HYPRE_BoomerAMGSetPMaxElmts(h.Amg, 4);
  HYPRE_BoomerAMGSetStrongThreshold(h.Amg, 0.5);
  HYPRE_BoomerAMGSetAggNumLevels(h.Amg, 1);
  // Plain Jacobi: the cheapest smoother setup (hypre's smoother is not used).
  HYPRE_BoomerAMGSetRelaxType(h.Amg, 0);
  Check(HYPRE_BoomerAMGSetup(h.Amg, par, parB, parX), "BoomerAMGSetup");

  hypre_ParAMGData* data = reinterpret_cast<hypre_ParAMGData*>(h.Amg);
  const int levels = hypre_ParAMGDataNumLevels(data);
  hypre_ParCSRMatrix** aArray = hypre_ParAMGDataAArray(data);
  hypre_ParCSRMatrix** pArray = hypre_ParAMGDataPArray(data);
  AmgHierarchy out;
  out.Operators.reserve(static_cast<std::size_t>(levels));
  out.Operators.push_back(a);
  for (int l = 1; l < levels; ++l)
  {
    out.Operators.push_back(CopyLocal(aArray[l], "coarse operator"));
  }
  for (int l = 0; l + 1 < levels; ++l)
  {
    out.Interpolations.push_back(CopyLocal(pArray[l], "interpolation"));
  }
  return out;
}

} // namespace av
