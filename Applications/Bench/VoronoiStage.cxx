// SPDX-License-Identifier: BSD-3-Clause
// The "voronoi" stage of anisovoronoi-bench: ComputeRestrictedVoronoi alone, its time and memory.
#include "VoronoiStage.h"

#include "ParticleSampler.h"
#include "RestrictedVoronoi.h"
#include "Stopwatch.h"

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <string>
#include <utility>

namespace avbench
{
namespace
{

// A "Key:   123 kB" line of /proc/self/status in MB (< 0 if absent).
double StatusMb(const std::string& key)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0)
      return std::stod(line.substr(key.size())) / 1024.0;
  return -1.0;
}

// Resets the peak resident set (VmHWM) to the current one; false where not allowed.
bool ResetPeakRss()
{
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

double CpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double MaxRssMb()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0; // Linux: kilobytes
}

template <class T>
double Bytes(const std::vector<T>& v)
{
  return static_cast<double>(v.capacity() * sizeof(T));
}

double DiagramMb(const av::RestrictedVoronoiDiagram& r)
{
  const double b = Bytes(r.PieceSite) + Bytes(r.PieceElement) + Bytes(r.PieceMeasure) +
    Bytes(r.PieceEmbeddedMeasure) + Bytes(r.PieceVertexOffsets) + Bytes(r.PieceFaceOffsets) +
    Bytes(r.Points) + Bytes(r.EmbeddedPoints) + Bytes(r.VertexPlanes) + Bytes(r.FaceOffsets) +
    Bytes(r.FaceVertices) + Bytes(r.FaceKind) + Bytes(r.FaceNeighbor) + Bytes(r.SiteMeasure) +
    Bytes(r.SiteEmbeddedMeasure) + Bytes(r.VoronoiVertexSites) + Bytes(r.VoronoiVertexElement) +
    Bytes(r.BoundaryDualFaces) + Bytes(r.ElementPieceOffsets) +
    Bytes(r.ElementVoronoiVertexOffsets) + Bytes(r.ElementBoundaryDualFaceOffsets) +
    Bytes(r.ElementNearestSite) + Bytes(r.ElementEmptyVisit) + Bytes(r.PieceSecurityRadius2) +
    Bytes(r.PieceLastCutDistance) + Bytes(r.ElementBoundaryFacets);
  return b / (1024.0 * 1024.0);
}

// Every output field, exactly (the fast path promises the same bits).
bool SameDiagram(const av::RestrictedVoronoiDiagram& a, const av::RestrictedVoronoiDiagram& b)
{
  return a.PieceSite == b.PieceSite && a.PieceElement == b.PieceElement &&
    a.PieceMeasure == b.PieceMeasure && a.PieceEmbeddedMeasure == b.PieceEmbeddedMeasure &&
    a.PieceVertexOffsets == b.PieceVertexOffsets && a.PieceFaceOffsets == b.PieceFaceOffsets &&
    a.Points == b.Points && a.EmbeddedPoints == b.EmbeddedPoints &&
    a.VertexPlanes == b.VertexPlanes && a.FaceOffsets == b.FaceOffsets &&
    a.FaceVertices == b.FaceVertices && a.FaceKind == b.FaceKind &&
    a.FaceNeighbor == b.FaceNeighbor && a.SiteMeasure == b.SiteMeasure &&
    a.SiteEmbeddedMeasure == b.SiteEmbeddedMeasure &&
    a.VoronoiVertexSites == b.VoronoiVertexSites &&
    a.VoronoiVertexElement == b.VoronoiVertexElement &&
    a.BoundaryDualFaces == b.BoundaryDualFaces && a.ElementPieceOffsets == b.ElementPieceOffsets &&
    a.ElementVoronoiVertexOffsets == b.ElementVoronoiVertexOffsets &&
    a.ElementBoundaryDualFaceOffsets == b.ElementBoundaryDualFaceOffsets &&
    a.ElementNearestSite == b.ElementNearestSite && a.ElementEmptyVisit == b.ElementEmptyVisit &&
    a.PieceSecurityRadius2 == b.PieceSecurityRadius2 &&
    a.PieceLastCutDistance == b.PieceLastCutDistance;
}

} // namespace

VoronoiStageResult RunVoronoiStage(const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  const MeshStageOptions& options,
  int repeats,
  bool geometry,
  bool embeddedPoints)
{
  VoronoiStageResult result;
  const av::Stopwatch sampleWatch;
  const av::SiteSet sites = av::SampleParticles(mesh, embedding, SamplerOptionsOf(options)).Sites;
  result.SampleSeconds = sampleWatch.Seconds();
  result.Sites = sites.NumSites();
  result.Elements = mesh.NumCells();
  // The adjacency once, as the pipeline does (not part of the RVD's time).
  const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(mesh);
  result.PeakIsReset = ResetPeakRss();
  for (int geom = 0; geom < (geometry ? 2 : 1); ++geom)
  {
    av::RestrictedVoronoiDiagram reference; // without the fast path
    for (int fast = 0; fast < 2; ++fast)
    {
      VoronoiRun run;
      run.Geometry = geom != 0;
      run.FastPath = fast != 0;
      av::RestrictedVoronoiOptions o;
      o.ComputeGeometry = run.Geometry;
      o.KeepEmbeddedPoints = embeddedPoints;
      o.WholeElementFastPath = run.FastPath;
      o.ElementAdjacency = &adjacency;
      av::RestrictedVoronoiDiagram r;
      for (int rep = 0; rep < std::max(1, repeats); ++rep)
      {
        r = av::RestrictedVoronoiDiagram(); // free the previous one before measuring
        malloc_trim(0);
        const double before = result.PeakIsReset ? StatusMb("VmRSS:") : MaxRssMb();
        if (result.PeakIsReset)
          ResetPeakRss();
        const av::Stopwatch watch;
        const double cpu0 = CpuSeconds();
        r = av::ComputeRestrictedVoronoi(mesh, embedding, sites, o);
        const double seconds = watch.Seconds(), cpu = CpuSeconds() - cpu0;
        const double peak = result.PeakIsReset ? StatusMb("VmHWM:") : MaxRssMb();
        run.BestSeconds = rep == 0 ? seconds : std::min(run.BestSeconds, seconds);
        run.BestCpuSeconds = rep == 0 ? cpu : std::min(run.BestCpuSeconds, cpu);
        if (before >= 0.0 && peak >= 0.0)
          run.PeakRssMb = std::max(run.PeakRssMb, peak - before);
      }
      run.OutputMb = DiagramMb(r);
      run.Pieces = r.NumPieces();
      run.Vertices = r.NumVertices();
      run.WholeElements = r.NumWholeElements;
      if (fast == 0)
        reference = std::move(r);
      else
        run.SameAsNoFastPath = SameDiagram(reference, r);
      result.Runs.push_back(run);
    }
  }
  return result;
}

} // namespace avbench
