// SPDX-License-Identifier: BSD-3-Clause
// BoomerAmgHierarchy: the coarse levels and interpolations of hypre's BoomerAMG setup, copied out
// of hypre, for the iterative global step's own V-cycle.
#ifndef av_BoomerAmgHierarchy_h
#define av_BoomerAmgHierarchy_h

#include "CsrMatrix.h"

#include <vector>

namespace av
{

/// A Galerkin hierarchy: Operators[0] is the input, Operators[l + 1] = P_l^T Operators[l] P_l with
/// P_l = Interpolations[l].
struct AmgHierarchy
{
  std::vector<CsrMatrix> Operators;
  std::vector<CsrMatrix> Interpolations;
};

/**
 * Runs BoomerAMGSetup on the symmetric matrix a (on MPI_COMM_SELF) and copies its levels:
 * HMIS coarsening, extended+i interpolation truncated to 4 entries per row, strength threshold
 * 0.5, one level of aggressive coarsening (the usual low-complexity choice for 3D scalar
 * problems). hypre does the part that is hard to do well (coarsening, interpolation, the
 * Galerkin products); the cycle that runs every iteration is ours (MultigridVCycle), threaded
 * and multi-vector, which Debian's serial hypre build is not.
 *
 * hypre is built with MPI in Debian: MPI is initialized (singleton) on first use if the process
 * has not done it, and finalized at exit. Calls into hypre are serialized by a mutex.
 * Throws InputError when hypre fails.
 */
AmgHierarchy BuildBoomerAmgHierarchy(const CsrMatrix& a);

} // namespace av

#endif
