// SPDX-License-Identifier: BSD-3-Clause
#include "TensorToMetric.h"

#include "MetricAlgebra.h"
#include "VertexGraph.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace av
{
namespace
{
template <int D>
using Mat = Eigen::Matrix<double, D, D>;
template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// Reads the used D x D block of tuple v; returns the symmetric part, sets the asymmetry.
template <int D>
Mat<D> ReadTensor(const double* v, int nc, double& asymmetry)
{
  Mat<D> t;
  if (nc == 9)
  {
    for (int i = 0; i < D; ++i)
    {
      for (int j = 0; j < D; ++j)
      {
        t(i, j) = v[3 * i + j];
      }
    }
    const double norm = t.norm();
    asymmetry = norm > 0.0 ? 0.5 * (t - t.transpose()).norm() / norm : 0.0;
    return 0.5 * (t + t.transpose());
  }
  asymmetry = 0.0;
  const Eigen::Matrix3d full = UnpackSymmetric(v);
  return full.template topLeftCorner<D, D>();
}

template <int D>
void Decompose(const Mat<D>& m, Vec<D>& values, Mat<D>& vectors)
{
  const auto e = EigenDecompose(m); // MetricAlgebra: ascending values, orthonormal vectors
  values = e.Values;
  vectors = e.Vectors;
}

template <int D>
void Write(const Mat<D>& m, double* out6)
{
  Eigen::Matrix3d full = Eigen::Matrix3d::Zero();
  full.template topLeftCorner<D, D>() = m;
  PackSymmetric(full, out6);
}

/// Log-Euclidean smoothing of the metrics (frame, eigenvalues) along the mesh edges: the
/// logarithms are averaged with HalfLaplacianStep, so the result stays SPD.
template <int D>
void SmoothLogEuclidean(std::size_t n,
  const std::vector<std::int32_t>& edges,
  int iterations,
  std::vector<Mat<D>>& frame,
  std::vector<Vec<D>>& metricEig)
{
  const tbb::blocked_range<std::size_t> all(0, n, 1024);
  const VertexGraph graph = BuildVertexGraph(n, edges);
  std::vector<Mat<D>> logM(n), next(n);
  tbb::parallel_for(all,
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        logM[i] =
          frame[i] * metricEig[i].array().log().matrix().asDiagonal() * frame[i].transpose();
      }
    });
  for (int it = 0; it < iterations; ++it)
  {
    HalfLaplacianStep(graph, logM, next);
    logM.swap(next);
  }
  tbb::parallel_for(all,
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        Vec<D> l;
        Decompose<D>(logM[i], l, frame[i]);
        metricEig[i] = l.array().exp().matrix();
      }
    });
}

template <int D>
TensorToMetricResult Convert(const double* tensors,
  std::size_t n,
  int nc,
  const TensorToMetricOptions& opt,
  const std::vector<std::int32_t>& edges)
{
  TensorToMetricResult r;
  std::vector<Vec<D>> lambda(n);
  std::vector<Mat<D>> frame(n);
  std::vector<double> asym(n);
  const tbb::blocked_range<std::size_t> all(0, n, 1024);
  tbb::parallel_for(all,
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const Mat<D> t = ReadTensor<D>(tensors + i * nc, nc, asym[i]);
        Decompose<D>(t, lambda[i], frame[i]);
      }
    });
  double maxAbs = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    maxAbs = std::max(maxAbs, lambda[i].cwiseAbs().maxCoeff());
    r.MaxAsymmetry = std::max(r.MaxAsymmetry, asym[i]);
  }
  if (!(maxAbs > 0.0))
  {
    throw InputError("TensorToMetric: every tensor is zero, so there is no direction or size to "
                     "build a metric from (is the right array selected?)");
  }
  const double floor = opt.MinimumEigenvalue * maxAbs;

  // Per tuple: f(lambda), floor, interpretation, anisotropy cap. flags: 1 negative, 2 clamped,
  // 4 capped.
  std::vector<unsigned char> flags(n, 0);
  std::vector<Vec<D>> metricEig(n);
  tbb::parallel_for(all,
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        unsigned char f = 0;
        Vec<D> s;
        for (int k = 0; k < D; ++k)
        {
          const double l = lambda[i][k];
          f |= (l < 0.0) ? 1 : 0;
          double v = opt.Eigenvalues == EigenvalueHandling::Absolute ? std::abs(l) : l;
          if (v < floor)
          {
            v = floor;
            f |= 2;
          }
          s[k] =
            opt.Interpretation == TensorInterpretation::EigenvaluesAsStretch ? v : std::sqrt(v);
        }
        if (opt.MaximumAnisotropy > 0.0)
        {
          const double lowest = s.maxCoeff() / opt.MaximumAnisotropy;
          if (s.minCoeff() < lowest * (1.0 - 1e-12))
          {
            s = s.cwiseMax(lowest);
            f |= 4;
          }
        }
        metricEig[i] = s.cwiseProduct(s);
        flags[i] = f;
      }
    });
  for (unsigned char f : flags)
  {
    r.NumNegative += (f & 1) != 0;
    r.NumClamped += (f & 2) != 0;
    r.NumCapped += (f & 4) != 0;
  }

  if (opt.SmoothingIterations > 0)
  {
    SmoothLogEuclidean<D>(n, edges, opt.SmoothingIterations, frame, metricEig);
  }

  double minEig = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
  {
    minEig = std::min(minEig, metricEig[i].minCoeff());
  }
  r.GlobalScale = (opt.ApplyGlobalScale && minEig < 1.0) ? 1.0 / minEig : 1.0;

  r.Metric.Values.assign(6 * n, 0.0);
  r.StretchRatio.assign(n, 1.0);
  tbb::parallel_for(all,
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
      {
        const Vec<D> mu = r.GlobalScale * metricEig[i];
        const Mat<D> m = frame[i] * mu.asDiagonal() * frame[i].transpose();
        Write<D>(m, r.Metric.Values.data() + 6 * i);
        r.StretchRatio[i] = std::sqrt(mu.maxCoeff() / mu.minCoeff());
      }
    });
  r.MinEigenvalue = std::numeric_limits<double>::infinity();
  r.MaxEigenvalue = 0.0;
  r.MinStretch = std::numeric_limits<double>::infinity();
  r.MaxStretch = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    r.MinEigenvalue = std::min(r.MinEigenvalue, r.GlobalScale * metricEig[i].minCoeff());
    r.MaxEigenvalue = std::max(r.MaxEigenvalue, r.GlobalScale * metricEig[i].maxCoeff());
    r.MinStretch = std::min(r.MinStretch, r.StretchRatio[i]);
    r.MaxStretch = std::max(r.MaxStretch, r.StretchRatio[i]);
  }
  return r;
}
} // namespace

TensorToMetricResult TensorToMetric(const double* tensors,
  std::size_t count,
  int numComponents,
  const TensorToMetricOptions& options,
  const std::vector<std::int32_t>& edges)
{
  const std::string who = "TensorToMetric: ";
  if (count == 0 || tensors == nullptr)
  {
    throw InputError(who + "the tensor array is empty");
  }
  if (numComponents != 6 && numComponents != 9)
  {
    throw InputError(who +
      "a tensor needs 9 components (3x3) or 6 (symmetric, XX YY ZZ XY YZ "
      "XZ), the array has " +
      std::to_string(numComponents));
  }
  if (options.Dimension != 2 && options.Dimension != 3)
  {
    throw InputError(who + "Dimension must be 2 or 3");
  }
  if (!(options.MinimumEigenvalue > 0.0 && options.MinimumEigenvalue <= 1.0))
  {
    throw InputError(who + "MinimumEigenvalue must be in (0, 1] (relative to the largest)");
  }
  if (!(options.MaximumAnisotropy == 0.0 || options.MaximumAnisotropy >= 1.0) ||
    !std::isfinite(options.MaximumAnisotropy))
  {
    throw InputError(who + "MaximumAnisotropy must be 0 (no cap) or >= 1");
  }
  if (options.SmoothingIterations < 0)
  {
    throw InputError(who + "SmoothingIterations must be >= 0");
  }
  if (options.SmoothingIterations > 0 && edges.empty())
  {
    throw InputError(who + "smoothing needs the mesh edges (none were given)");
  }
  if (edges.size() % 2 != 0)
  {
    throw InputError(who + "the edge list must hold pairs of ids");
  }
  for (std::int32_t e : edges)
  {
    if (e < 0 || static_cast<std::size_t>(e) >= count)
    {
      throw InputError(who + "edge references tuple " + std::to_string(e) + ", outside [0, " +
        std::to_string(count) + ")");
    }
  }
  // Only the components the dimension uses must be finite.
  const int used9[2][9] = { { 1, 1, 0, 1, 1, 0, 0, 0, 0 }, { 1, 1, 1, 1, 1, 1, 1, 1, 1 } };
  const int used6[2][6] = { { 1, 1, 0, 1, 0, 0 }, { 1, 1, 1, 1, 1, 1 } };
  const int* used =
    numComponents == 9 ? used9[options.Dimension - 2] : used6[options.Dimension - 2];
  for (std::size_t i = 0; i < count; ++i)
  {
    for (int k = 0; k < numComponents; ++k)
    {
      if (used[k] && !std::isfinite(tensors[i * numComponents + k]))
      {
        throw InputError(who + "tensor " + std::to_string(i) + " has a NaN or infinite value");
      }
    }
  }
  return options.Dimension == 2 ? Convert<2>(tensors, count, numComponents, options, edges)
                                : Convert<3>(tensors, count, numComponents, options, edges);
}

} // namespace av

namespace av
{
TensorToMetricResult TangentTensorToMetric(const double* tensors, std::size_t count,
  int numComponents, const double* normals, TensorToMetricOptions options)
{
  if (numComponents != 6 && numComponents != 9)
  {
    throw InputError("TangentTensorToMetric: tensors need 6 or 9 components");
  }
  if (options.SmoothingIterations > 0)
  {
    throw InputError("TangentTensorToMetric: smoothing is not available with the tangent-plane "
                     "projection (smooth the tensor field first)");
  }
  if (count > 0 && (!tensors || !normals))
  {
    throw InputError("TangentTensorToMetric: null tensors or normals");
  }
  // Per tuple a frame R = [t1 t2 n]; the tensor in it, R^T T R, keeps its 9 or 6 components
  // (9: the asymmetry survives, so TensorToMetric still reports it).
  std::vector<Eigen::Matrix3d> frames(count);
  std::vector<double> local(count * static_cast<std::size_t>(numComponents));
  for (std::size_t i = 0; i < count; ++i)
  {
    const Eigen::Vector3d n(normals + 3 * i);
    if (!(n.norm() > 0.5) || !n.allFinite())
    {
      throw InputError("TangentTensorToMetric: normal " + std::to_string(i) + " is not a unit vector");
    }
    const Eigen::Vector3d u = n.normalized();
    // The axis least aligned with n gives a well-conditioned first tangent.
    int axis = 0;
    u.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d t1 = u.cross(Eigen::Vector3d::Unit(axis)).normalized();
    Eigen::Matrix3d R;
    R << t1, u.cross(t1), u;
    frames[i] = R;
    const double* t = tensors + i * numComponents;
    double* out = local.data() + i * numComponents;
    if (numComponents == 9)
    {
      const Eigen::Matrix3d T = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(t);
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> outMap(out);
      outMap = R.transpose() * T * R;
    }
    else
    {
      PackSymmetric(R.transpose() * UnpackSymmetric(t) * R, out);
    }
  }
  options.Dimension = 2; // the tangent block XX, YY, XY of the local frame
  TensorToMetricResult r = TensorToMetric(local.data(), count, numComponents, options);
  for (std::size_t i = 0; i < count; ++i)
  {
    double* m = r.Metric.Values.data() + 6 * i;
    Eigen::Matrix3d local3 = Eigen::Matrix3d::Zero();
    local3(0, 0) = m[0];
    local3(1, 1) = m[1];
    local3(0, 1) = local3(1, 0) = m[3];
    PackSymmetric(frames[i] * local3 * frames[i].transpose(), m);
  }
  return r;
}
} // namespace av
