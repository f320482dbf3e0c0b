// SPDX-License-Identifier: BSD-3-Clause
#include "RealCases.h"

#include "FrdReader.h"
#include "MeshTopology.h"
#include "OffReader.h"
#include "SimplexSplitter.h"
#include "SurfaceCurvatureMetric.h"
#include "TensorToMetric.h"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace avbench
{
namespace
{
const std::string kPrefix = "real:";

bool Readable(const std::string& path)
{
  std::ifstream f(path);
  return f.good();
}

const RealCaseInfo& FindCase(const std::string& name)
{
  const std::string bare = IsRealCaseName(name) ? name.substr(kPrefix.size()) : name;
  for (const RealCaseInfo& c : RealCases())
  {
    if (c.Name == bare)
    {
      return c;
    }
  }
  std::string known;
  for (const RealCaseInfo& c : RealCases())
  {
    known += " real:" + c.Name;
  }
  throw std::runtime_error("unknown real case '" + name + "' (known:" + known + ", real:all)");
}

/// The .frd mesh in VTK layout (VTK cell type ids and node order) for SplitIntoSimplices.
av::SimplexSplitResult SplitFrd(const av::FrdData& d)
{
  std::vector<std::uint8_t> types(d.NumElements());
  std::vector<std::int64_t> offsets(d.NumElements() + 1, 0), connectivity;
  connectivity.reserve(d.Connectivity.size());
  for (std::size_t e = 0; e < d.NumElements(); ++e)
  {
    const int t = d.ElementTypes[e];
    const int* order = av::FrdToVTKNodeOrder(t);
    const int n = av::FrdNodesPerElement(t);
    types[e] = static_cast<std::uint8_t>(av::FrdToVTKCellType(t));
    for (int i = 0; i < n; ++i)
    {
      connectivity.push_back(d.Connectivity[d.Offsets[e] + order[i]]);
    }
    offsets[e + 1] = static_cast<std::int64_t>(connectivity.size());
  }
  return av::SplitIntoSimplices(d.Points.data(),
    d.NumNodes(),
    types.data(),
    offsets.data(),
    connectivity.data(),
    d.NumElements(),
    3);
}

/// Tensor (6 components) of every split point: the weighted mean of its parents' tensors,
/// as vtkAnisoSimplexMesh interpolates point data.
std::vector<double> InterpolateTensors(const av::SimplexSplitResult& s, const av::FrdResult& r)
{
  const std::size_t n = s.Mesh.NumPoints();
  std::vector<double> t(6 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::int64_t k = s.PointParentOffsets[i]; k < s.PointParentOffsets[i + 1]; ++k)
    {
      const double w = s.PointWeights[k];
      const double* src = r.Values.data() + 6 * s.PointParents[k];
      for (int c = 0; c < 6; ++c)
      {
        t[6 * i + c] += w * src[c];
      }
    }
  }
  return t;
}

RealInput LoadVolume(const RealCaseInfo& info, const std::string& path, const RealCaseOptions& o)
{
  const av::FrdData d = av::ReadFrd(path);
  const std::vector<int> steps = d.Steps();
  if (info.StepIndex >= static_cast<int>(steps.size()))
  {
    throw std::runtime_error(path + " has " + std::to_string(steps.size()) +
      " step(s), the case needs step index " + std::to_string(info.StepIndex));
  }
  const int ri = d.FindResult(info.Field, steps[info.StepIndex]);
  if (ri < 0 || !d.Results[ri].IsSymmetricTensor)
  {
    throw std::runtime_error(path + " has no symmetric tensor result " + info.Field);
  }
  RealInput in;
  in.FilePoints = d.NumNodes();
  in.FileCells = d.NumElements();
  av::SimplexSplitResult split = SplitFrd(d);
  const std::vector<double> tensors = InterpolateTensors(split, d.Results[ri]);
  av::TensorToMetricOptions mo;
  mo.MinimumEigenvalue = o.MinEigenvalue;
  mo.MaximumAnisotropy = o.MaxAnisotropy;
  mo.SmoothingIterations = o.SmoothingIterations;
  const av::TensorToMetricResult m = av::TensorToMetric(tensors.data(),
    split.Mesh.NumPoints(),
    6,
    mo,
    o.SmoothingIterations > 0 ? av::UniqueEdges(split.Mesh) : std::vector<std::int32_t>());
  in.Mesh = std::move(split.Mesh);
  in.Metric = m.Metric;
  in.StretchMin = m.MinStretch;
  in.StretchMax = m.MaxStretch;
  in.Description = info.File + " " + info.Field + " step " + std::to_string(steps[info.StepIndex]) +
    " -> " + std::to_string(in.Mesh.NumCells()) + " tets";
  return in;
}

RealInput LoadSurface(const RealCaseInfo& info, const std::string& path, const RealCaseOptions& o)
{
  RealInput in;
  in.IsSurface = true;
  in.Mesh = av::ReadOff(path);
  in.FilePoints = in.Mesh.NumPoints();
  in.FileCells = in.Mesh.NumCells();
  av::SurfaceCurvatureMetricOptions mo;
  mo.CreaseAngle = o.CreaseAngle;
  const av::SurfaceCurvatureMetricResult m = av::SurfaceCurvatureMetric(in.Mesh, mo);
  in.Metric = m.Metric;
  in.CreaseEdges = m.NumCreaseEdges;
  const auto range = std::minmax_element(m.StretchRatio.begin(), m.StretchRatio.end());
  in.StretchMin = *range.first;
  in.StretchMax = *range.second;
  in.Description = info.File + " curvature -> " + std::to_string(in.Mesh.NumCells()) + " triangles";
  return in;
}
} // namespace

const std::vector<RealCaseInfo>& RealCases()
{
  // Steps: the compressor's first mode as the main job; segmenttet's second mode (its first
  // is a near rigid-body mode); the static decks have one increment.
  static const std::vector<RealCaseInfo> cases = {
    { "compressor", "compressor.frd", "STRESS", 0 },
    { "rotor", "ccx-rotor.frd", "STRESS", 0 },
    { "segmenttet", "ccx-segmenttet.frd", "STRESS", 1 },
    { "cubef2f1", "ccx-cubef2f1.frd", "STRESS", 0 },
    { "hueeber1", "ccx-hueeber1.frd", "STRESS", 0 },
    { "squarebend", "foam-squarebend.frd", "SRATE", 0 },
    { "mixer", "foam-mixer.frd", "SRATE", 0 },
    { "turbine", "turbine.off", "", 0 },
    { "knot1", "knot1.off", "", 0 },
    { "mushroom", "mushroom.off", "", 0 },
    { "fandisk", "fandisk_large.off", "", 0 },
  };
  return cases;
}

bool IsRealCaseName(const std::string& caseName)
{
  return caseName.rfind(kPrefix, 0) == 0;
}

std::string RealDataDirectory(const std::string& option)
{
  if (!option.empty())
  {
    return option;
  }
  if (const char* env = std::getenv("AV_REAL_DATA_DIR"))
  {
    if (*env)
    {
      return env;
    }
  }
  std::string exe(4096, '\0');
  const ssize_t n = readlink("/proc/self/exe", exe.data(), exe.size() - 1);
  if (n <= 0)
  {
    return "real-data";
  }
  exe.resize(static_cast<std::size_t>(n));
  const std::size_t slash = exe.rfind('/'); // .../build/bin/anisovoronoi-bench
  const std::string binDir = exe.substr(0, slash == std::string::npos ? 0 : slash);
  const std::size_t up = binDir.rfind('/');
  return (up == std::string::npos ? std::string(".") : binDir.substr(0, up)) + "/real-data";
}

RealInput LoadRealCase(const std::string& name,
  const std::string& dataDir,
  const RealCaseOptions& options)
{
  const RealCaseInfo& info = FindCase(name);
  const std::string path = dataDir + "/" + info.File;
  if (!Readable(path))
  {
    throw std::runtime_error("real data missing: " + path +
      " (make it with scripts/make-real-data.sh " + dataDir +
      ", or point --data-dir / AV_REAL_DATA_DIR at it)");
  }
  return info.Field.empty() ? LoadSurface(info, path, options) : LoadVolume(info, path, options);
}

std::size_t DefaultRealSites(const RealInput& input)
{
  return input.IsSurface ? 2000 : 3000;
}

} // namespace avbench
