// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoParticleSampler
 * @brief Isotropic particle sampling of the embedded mesh (paper §4.1): sites whose spacing in
 * R^m̄ is uniform, hence anisotropic (following the metric) in the input space.
 *
 * Input: the output of vtkAnisoEmbedding, a triangle / tetrahedral mesh with an embedding point
 * array (m̄ components, the first m equal to the input coordinates), chosen with
 * SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name); default
 * "Embedding".
 *
 * NumberOfSites particles are drawn on the embedded mesh (probability proportional to the
 * embedded element measure) and spread by minimizing the Gaussian repulsion energy
 * E = sum exp(-|x_p - x_q|^2 / (4 sigma^2)),
 * sigma = KernelWidthFactor (|embedded mesh| / n)^{1/k},
 * over pairs closer than NeighborCutoff sigma (projected L-BFGS, particles stay on / in the
 * embedded mesh). Deterministic for a given Seed.
 *
 * Output 0 (vtkPolyData): one vertex cell per site at its input-space position (the first m
 * embedded coordinates; z = 0 for a flat 2D domain), with point arrays
 * - "Embedding": m̄ components, the embedded position;
 * - "CellId": index of the containing triangle / tetrahedron (= input cell id when the input
 *   has only triangles / tetrahedra);
 * - "Barycentric": 4 components, barycentric coordinates in that cell (4th = 0 for triangles);
 * - "FeatureKind": 0 for a free site, 1 for a site on a feature line, 2 for a corner site
 *   (vtkAnisoRestrictedDelaunay keeps the last two on their features);
 * - "Metric": the input's metric (6 components) interpolated at the site, when the input has
 *   one (active point tensors or an array named "Metric").
 * Field data: "Sigma", "EmbeddedMeasure", "MeanNeighbors", "SamplerIterations",
 * "SamplerWarmupIterations", "SamplerSeconds", "NumCornerSites", "NumFeatureLineSites".
 * Output 1 (vtkTable): "Iteration", "Energy" per iteration at the final kernel (0 = their
 * start: the initial sampling, or the sites after the warm-up).
 *
 * Parameters: NumberOfSites (default 2000; between 1 and 8 x the input's point count),
 * Iterations (150), WarmupIterations (100), PreserveSharpFeatures (on), FeatureAngle (30),
 * Seed (1), KernelWidthFactor (0.3), NeighborCutoff (5).
 *
 * Distributed runs (mpiexec pvbatch, pvserver): needs the whole mesh, so it asks its inputs
 * for the whole dataset and runs redundantly on every process that needs its output (the cost
 * is not divided); the whole result goes to piece 0 and the other pieces are empty, so that
 * gathering the pieces gives one copy. See Documentation/parallel.md.
 */
#ifndef vtkAnisoParticleSampler_h
#define vtkAnisoParticleSampler_h

#include "AnisoVoronoiFiltersSamplingModule.h" // export macro
#include <vtkPolyDataAlgorithm.h>

class ANISOVORONOIFILTERSSAMPLING_EXPORT vtkAnisoParticleSampler : public vtkPolyDataAlgorithm
{
public:
  static vtkAnisoParticleSampler* New();
  vtkTypeMacro(vtkAnisoParticleSampler, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Number of sites n (default 2000). 0 or more than 8 x the input's point count is an error.
  vtkSetClampMacro(NumberOfSites, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfSites, int);
  ///@}

  ///@{
  /// L-BFGS iterations of the repulsion (default 150; the paper: 50; 0 = random sampling
  /// only, after any warm-up).
  vtkSetClampMacro(Iterations, int, 0, 100000);
  vtkGetMacro(Iterations, int);
  ///@}

  ///@{
  /// Iterations at a narrower kernel (0.25 / 0.3 of sigma's factor) run before Iterations
  /// (default 100; not in the paper). They help short runs (Cube1 G_avg 0.907 with 100 + 50
  /// vs 0.905 with 150 at the paper's kernel) and hurt long ones (2000 iterations: 0.917
  /// after a warm-up, 0.927 without): set 0 with Iterations of 1000 or more.
  vtkSetClampMacro(WarmupIterations, int, 0, 100000);
  vtkGetMacro(WarmupIterations, int);
  ///@}

  ///@{
  /// Sharp features (paper §4.1, default on): one fixed site at every corner of the input
  /// mesh and sites that move only along its feature lines (boundary edges whose dihedral
  /// angle exceeds FeatureAngle), so that the dual mesh keeps the domain's corners and
  /// edges. Smooth domains are unaffected.
  vtkSetMacro(PreserveSharpFeatures, bool);
  vtkGetMacro(PreserveSharpFeatures, bool);
  vtkBooleanMacro(PreserveSharpFeatures, bool);
  ///@}

  ///@{
  /// Dihedral angle in degrees above which an edge is a feature line (default 30, as
  /// vtkFeatureEdges; 180 = none).
  vtkSetClampMacro(FeatureAngle, double, 1e-3, 180.0);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /// Feature lines given instead of found by FeatureAngle (triangle surfaces): the name of an
  /// integer cell array of patch ids (CAD faces, the Medit reader's triangle "Ref", region
  /// ids); the edges between triangles of different ids are the feature lines, whatever their
  /// angle. Corners as usual, plus the points where FeatureCornerArray (an optional point
  /// array) is nonzero. Empty (default): found by FeatureAngle. A named array that is missing
  /// or has more than one component is an error.
  vtkSetStringMacro(FeaturePatchArray);
  vtkGetStringMacro(FeaturePatchArray);
  vtkSetStringMacro(FeatureCornerArray);
  vtkGetStringMacro(FeatureCornerArray);
  ///@}

  ///@{
  /// Seed of the initial random sampling (default 1): same seed, same sites.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// sigma = KernelWidthFactor * (|embedded mesh| / n)^{1/k} (default 0.3, the paper's).
  vtkSetClampMacro(KernelWidthFactor, double, 1e-3, 10.0);
  vtkGetMacro(KernelWidthFactor, double);
  ///@}

  ///@{
  /// Pairs farther apart than NeighborCutoff * sigma do not interact (default 5).
  vtkSetClampMacro(NeighborCutoff, double, 1.0, 20.0);
  vtkGetMacro(NeighborCutoff, double);
  ///@}

  /// Kernel width of the last run (also in the output's field data).
  vtkGetMacro(Sigma, double);

protected:
  vtkAnisoParticleSampler();
  ~vtkAnisoParticleSampler() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfSites = 2000;
  int Iterations = 150;
  int WarmupIterations = 100;
  bool PreserveSharpFeatures = true;
  double FeatureAngle = 30.0;
  char* FeaturePatchArray = nullptr;
  char* FeatureCornerArray = nullptr;
  int Seed = 1;
  double KernelWidthFactor = 0.3;
  double NeighborCutoff = 5.0;
  double Sigma = 0.0;

private:
  vtkAnisoParticleSampler(const vtkAnisoParticleSampler&) = delete;
  void operator=(const vtkAnisoParticleSampler&) = delete;
};

#endif
