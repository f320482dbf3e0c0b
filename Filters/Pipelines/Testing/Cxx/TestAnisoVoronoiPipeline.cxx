// SPDX-License-Identifier: BSD-3-Clause
// The 2D chain of the paper (Gaussian2D, §6.2): analytic source -> embedding (3D) -> particle
// sampler (300 sites) -> restricted Delaunay mesh -> quality. Checks the dual mesh is a valid
// triangulated disk (no inverted triangle, every interior edge in exactly two triangles, the
// boundary edges form one closed loop, Euler characteristic 1, one vertex per site), the
// anisotropic quality bound, determinism of the sampler, and errors on bad input.
#include "vtkAnisoAnalyticMetricSource.h"
#include "vtkAnisoEmbedding.h"
#include "vtkAnisoMeshQuality.h"
#include "vtkAnisoParticleSampler.h"
#include "vtkAnisoRestrictedDelaunay.h"
#include "vtkAnisoRestrictedVoronoi.h"
#include "Stopwatch.h"
#include "vtkAnisoTestUtilities.h"

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>

using av_vtk_test::EventCounter;
using av_vtk_test::FieldValue;

namespace
{
/// The 2D chain, built and run once: source -> embedding -> sampler -> RDT -> quality.
struct Chain
{
  vtkNew<vtkAnisoAnalyticMetricSource> source;
  vtkNew<vtkAnisoEmbedding> embedding;
  vtkNew<vtkAnisoParticleSampler> sampler;
  vtkNew<vtkAnisoRestrictedDelaunay> rdt;
  vtkNew<vtkAnisoMeshQuality> quality;
};

void RunChain(Chain& chain)
{
  vtkAnisoAnalyticMetricSource* source = chain.source;
  vtkAnisoEmbedding* embedding = chain.embedding;
  vtkAnisoParticleSampler* sampler = chain.sampler;
  vtkAnisoRestrictedDelaunay* rdt = chain.rdt;
  vtkAnisoMeshQuality* quality = chain.quality;
  source->SetPreset(0); // Gaussian2D on [-1, 1]^2
  source->SetResolution(30);
  embedding->SetInputConnection(source->GetOutputPort());
  embedding->SetTargetDimension(3);
  sampler->SetInputConnection(embedding->GetOutputPort());
  sampler->SetNumberOfSites(300);
  rdt->SetInputConnection(0, embedding->GetOutputPort());
  rdt->SetInputConnection(1, sampler->GetOutputPort());
  quality->SetInputConnection(rdt->GetOutputPort());
  av::Stopwatch t0;
  embedding->Update();
  std::printf(
    "embedding %.3f s, L_avg %.3g %%\n", t0.Seconds(), embedding->GetAverageEdgeLengthError());
  t0.Restart();
  sampler->Update();
  std::printf("sampler %.3f s, sigma %.4g\n", t0.Seconds(), sampler->GetSigma());
  t0.Restart();
  quality->Update();
  std::printf("RDT + quality %.3f s\n", t0.Seconds());
}

void CheckSites(vtkAnisoParticleSampler* sampler)
{
  vtkPolyData* sites = sampler->GetOutput();
  AV_CHECK(sites->GetNumberOfPoints() == 300);
  AV_CHECK(sites->GetNumberOfVerts() == 300);
  AV_CHECK(sites->GetPointData()->GetArray("Embedding") &&
    sites->GetPointData()->GetArray("Embedding")->GetNumberOfComponents() == 3);
  AV_CHECK(sites->GetPointData()->GetArray("Metric") != nullptr);
  vtkTable* energy = vtkTable::SafeDownCast(sampler->GetOutputDataObject(1));
  AV_CHECK(energy && energy->GetNumberOfRows() >= 2);
  if (energy && energy->GetNumberOfRows() >= 2)
    AV_CHECK(energy->GetValueByName(energy->GetNumberOfRows() - 1, "Energy").ToDouble() <
      energy->GetValueByName(0, "Energy").ToDouble());
}

// The dual mesh is a valid triangulated disk with one vertex per site.
void CheckDualMeshIsDisk(vtkUnstructuredGrid* mesh)
{
  const vtkIdType nc = mesh->GetNumberOfCells();
  std::printf("RDT: %lld triangles, %g inverted, %g non-manifold, %g open, %g unused\n",
    static_cast<long long>(nc),
    FieldValue(mesh, "NumInverted"),
    FieldValue(mesh, "NumNonManifoldFaces"),
    FieldValue(mesh, "NumOpenInteriorFaces"),
    FieldValue(mesh, "NumUnusedSites"));
  // The mesh improvement's splits append sites, its collapses leave unused points.
  const double splits = FieldValue(mesh, "NumImprovementSplits");
  const double collapses = FieldValue(mesh, "NumImprovementCollapses");
  AV_CHECK(mesh->GetNumberOfPoints() == 300 + static_cast<vtkIdType>(splits));
  AV_CHECK(FieldValue(mesh, "NumInverted") == 0);
  AV_CHECK(FieldValue(mesh, "NumNonManifoldFaces") == 0);
  AV_CHECK_MSG(FieldValue(mesh, "NumUnusedSites") == collapses,
    FieldValue(mesh, "NumUnusedSites") << " unused sites, " << collapses << " collapses");
  AV_CHECK(mesh->GetPointData()->GetArray("Metric") != nullptr);
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  vtkNew<vtkIdList> ids;
  int notTriangles = 0, negative = 0;
  for (vtkIdType c = 0; c < nc; ++c)
  {
    if (mesh->GetCellType(c) != VTK_TRIANGLE)
    {
      ++notTriangles;
      continue;
    }
    mesh->GetCellPoints(c, ids);
    double p[3][3];
    for (int a = 0; a < 3; ++a)
    {
      mesh->GetPoint(ids->GetId(a), p[a]);
      const vtkIdType u = ids->GetId(a), v = ids->GetId((a + 1) % 3);
      ++edges[{ std::min(u, v), std::max(u, v) }];
    }
    const double area2 =
      (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    negative += area2 <= 0;
    AV_CHECK(mesh->GetCellData()->GetArray("Inverted")->GetTuple1(c) == (area2 <= 0 ? 1 : 0));
  }
  AV_CHECK(notTriangles == 0);
  AV_CHECK(negative == 0);
  int boundaryEdges = 0, overused = 0;
  std::map<vtkIdType, int> boundaryDegree;
  for (const auto& e : edges)
  {
    overused += e.second > 2;
    if (e.second == 1)
    {
      ++boundaryEdges;
      ++boundaryDegree[e.first.first];
      ++boundaryDegree[e.first.second];
    }
  }
  int badBoundaryVertex = 0;
  for (const auto& d : boundaryDegree)
    badBoundaryVertex += d.second != 2;
  std::set<vtkIdType> used;
  for (const auto& e : edges)
  {
    used.insert(e.first.first);
    used.insert(e.first.second);
  }
  AV_CHECK(used.size() == static_cast<std::size_t>(mesh->GetNumberOfPoints() - collapses));
  const long long euler =
    static_cast<long long>(used.size()) - static_cast<long long>(edges.size()) + nc;
  std::printf(
    "edges %zu (boundary %d), Euler characteristic %lld\n", edges.size(), boundaryEdges, euler);
  AV_CHECK(overused == 0);
  AV_CHECK(boundaryEdges > 0);
  AV_CHECK(badBoundaryVertex == 0);
  AV_CHECK(euler == 1);
}

// Quality (paper §5.2): measured G_avg 0.86 here; the bound leaves a margin.
void CheckQuality(vtkAnisoMeshQuality* quality, vtkIdType nc)
{
  vtkUnstructuredGrid* q = quality->GetOutput();
  const double gavg = FieldValue(q, "G_avg");
  std::printf("quality: G_min %.3f G_avg %.3f theta_min %.2f theta_avg %.2f bad %.2f %% "
              "inverted %g unit edges %.1f %%\n",
    FieldValue(q, "G_min"),
    gavg,
    FieldValue(q, "theta_min"),
    FieldValue(q, "theta_avg"),
    FieldValue(q, "pct_bad"),
    FieldValue(q, "inverted"),
    FieldValue(q, "edges_in_unit_range"));
  AV_CHECK(gavg >= 0.8);
  AV_CHECK(FieldValue(q, "inverted") == 0);
  AV_CHECK(q->GetCellData()->GetArray("G") && q->GetCellData()->GetArray("MinAngle"));
  vtkTable* hist = vtkTable::SafeDownCast(quality->GetOutputDataObject(1));
  AV_CHECK(hist && hist->GetNumberOfRows() == 18);
  if (hist)
  {
    long long total = 0;
    for (vtkIdType r = 0; r < hist->GetNumberOfRows(); ++r)
      total += hist->GetValueByName(r, "Count").ToInt();
    AV_CHECK(total == nc);
  }
}

// The Voronoi cells of the same sites tile the square.
void CheckVoronoiTiles(Chain& chain)
{
  vtkAnisoEmbedding* embedding = chain.embedding;
  vtkAnisoParticleSampler* sampler = chain.sampler;
  vtkNew<vtkAnisoRestrictedVoronoi> rvd;
  rvd->SetInputConnection(0, embedding->GetOutputPort());
  rvd->SetInputConnection(1, sampler->GetOutputPort());
  rvd->Update();
  AV_CHECK(FieldValue(rvd->GetOutput(), "RelativeVolumeError") < 1e-9);
  AV_CHECK(std::abs(FieldValue(rvd->GetOutput(), "DomainMeasure") - 4.0) < 1e-9);
  std::printf("RVD: %lld polygons for 300 sites\n",
    static_cast<long long>(rvd->GetOutput()->GetNumberOfCells()));
  AV_CHECK(rvd->GetOutput()->GetNumberOfCells() >= 300);
}

// Same seed -> identical sites; another seed -> different sites.
void CheckSamplerDeterminism(Chain& chain)
{
  vtkAnisoEmbedding* embedding = chain.embedding;
  vtkPolyData* sites = chain.sampler->GetOutput();
  vtkNew<vtkAnisoParticleSampler> again;
  again->SetInputConnection(embedding->GetOutputPort());
  again->SetNumberOfSites(300);
  again->Update();
  vtkDataArray* a = sites->GetPointData()->GetArray("Embedding");
  vtkDataArray* b = again->GetOutput()->GetPointData()->GetArray("Embedding");
  bool same = a->GetNumberOfTuples() == b->GetNumberOfTuples();
  for (vtkIdType i = 0; same && i < a->GetNumberOfTuples(); ++i)
    for (int d = 0; d < 3; ++d)
      same = same && a->GetComponent(i, d) == b->GetComponent(i, d);
  AV_CHECK(same);
  again->SetSeed(7);
  again->Update();
  b = again->GetOutput()->GetPointData()->GetArray("Embedding");
  AV_CHECK(b->GetComponent(0, 0) != a->GetComponent(0, 0) ||
    b->GetComponent(0, 1) != a->GetComponent(0, 1));
}

// Bad inputs: errors, no crash.
void CheckBadInputs(Chain& chain)
{
  vtkAnisoAnalyticMetricSource* source = chain.source;
  vtkAnisoEmbedding* embedding = chain.embedding;
  vtkUnstructuredGrid* mesh = chain.rdt->GetOutput();
  vtkNew<EventCounter> errors;
  vtkNew<vtkAnisoParticleSampler> zero;
  zero->AddObserver(vtkCommand::ErrorEvent, errors);
  zero->SetInputConnection(embedding->GetOutputPort());
  zero->SetNumberOfSites(0);
  zero->Update();
  AV_CHECK(errors->Errors == 1);
  std::printf("0 sites -> \"%s\"\n", errors->Last.c_str());
  zero->SetNumberOfSites(100000000); // more than 8 x the mesh's points
  zero->Update();
  AV_CHECK(errors->Errors == 2);
  std::printf("too many sites -> \"%s\"\n", errors->Last.c_str());

  vtkNew<vtkAnisoParticleSampler> noEmbedding;
  noEmbedding->AddObserver(vtkCommand::ErrorEvent, errors);
  noEmbedding->SetInputConnection(source->GetOutputPort());
  noEmbedding->Update();
  AV_CHECK(errors->Errors == 3);
  AV_CHECK(errors->Last.find("embedding") != std::string::npos);
  AV_CHECK(noEmbedding->GetOutput()->GetNumberOfPoints() == 0);
  std::printf("no embedding -> \"%s\"\n", errors->Last.c_str());

  vtkNew<vtkPolyData> outside;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0.0, 0.0, 0.0);
  pts->InsertNextPoint(5.0, 5.0, 0.0); // outside [-1, 1]^2
  outside->SetPoints(pts);
  vtkNew<vtkAnisoRestrictedDelaunay> badSites;
  badSites->AddObserver(vtkCommand::ErrorEvent, errors);
  badSites->SetInputConnection(0, embedding->GetOutputPort());
  badSites->SetInputData(1, outside);
  badSites->Update();
  AV_CHECK(errors->Errors == 4);
  AV_CHECK(errors->Last.find("outside") != std::string::npos);
  AV_CHECK(badSites->GetOutput()->GetNumberOfCells() == 0);
  std::printf("site outside -> \"%s\"\n", errors->Last.c_str());

  vtkNew<vtkAnisoMeshQuality> noMetric;
  noMetric->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkNew<vtkUnstructuredGrid> bare;
  bare->CopyStructure(mesh);
  noMetric->SetInputData(bare);
  noMetric->Update();
  AV_CHECK(errors->Errors == 5);
  std::printf("no metric -> \"%s\"\n", errors->Last.c_str());
}
} // namespace

int TestAnisoVoronoiPipeline(int, char*[])
{
  Chain chain;
  RunChain(chain);
  CheckSites(chain.sampler);
  CheckDualMeshIsDisk(chain.rdt->GetOutput());
  CheckQuality(chain.quality, chain.rdt->GetOutput()->GetNumberOfCells());
  CheckVoronoiTiles(chain);
  CheckSamplerDeterminism(chain);
  CheckBadInputs(chain);
  return AV_TEST_RESULT();
}
