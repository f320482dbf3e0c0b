// SPDX-License-Identifier: BSD-3-Clause
// AndersonAcceleration: type-II Anderson extrapolation of a fixed-point iteration x -> G(x).
#ifndef av_AndersonAcceleration_h
#define av_AndersonAcceleration_h

#include <Eigen/Dense>

#include <vector>

namespace av
{

/**
 * Type-II Anderson acceleration over a window of previous iterates (the embedding's local/global
 * map, Peng et al. 2018). The Gram matrix of the residual differences gains one row per
 * iteration, and the dot products / combinations are fused parallel passes with fixed chunks
 * summed in order (deterministic, memory-bound). The caller keeps the candidate only when it
 * lowers its energy.
 */
class AndersonAcceleration
{
public:
  /// `window`: previous iterates used (0: Extrapolate never gives a candidate).
  explicit AndersonAcceleration(int window);

  /**
   * Records this iteration's pair (x, g = G(x)), residual f = g − x, and writes the candidate
   * xa = g − Σ_a θ_a ΔG_a with θ the least-squares fit of f by the residual differences ΔF_a.
   * Returns false when there is none (window 0, first iteration, non-finite θ).
   */
  bool Extrapolate(const Eigen::MatrixXd& x, const Eigen::MatrixXd& g, Eigen::MatrixXd& xa);

private:
  /// Stores ΔG, ΔF of the new pair in the ring buffer and updates the Gram matrix.
  void AddDifferences(const Eigen::MatrixXd& g);

  int Window = 0;
  int Head = 0; // oldest slot once the window is full
  std::vector<Eigen::MatrixXd> DG, DF;
  Eigen::MatrixXd GPrev, FPrev, F;
  Eigen::MatrixXd Gram;
  std::vector<double> Dots;
};

} // namespace av

#endif
