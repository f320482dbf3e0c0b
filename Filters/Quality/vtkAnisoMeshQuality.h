// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoMeshQuality
 * @brief The anisotropic mesh quality measures of the paper §5.2 (columns of Tab. 3 / Tab. 5).
 *
 * Input: a triangle (2D domain or surface) or tetrahedral mesh with a symmetric metric point
 * array (6 components XX, YY, ZZ, XY, YZ, XZ, or 9), chosen with SetInputArrayToProcess(0, 0,
 * 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name); by default the active point tensors, else
 * "Metric" (the output of vtkAnisoRestrictedDelaunay carries it from the sampler).
 *
 * Each cell is mapped by the average of its vertices' metric square roots, then
 * - triangles: G = 2 sqrt3 S / (p h), theta = smallest angle, "bad" if theta < 30 deg;
 * - tetrahedra: G = 12 (9 V^2)^{1/3} / sum l^2, theta = smallest dihedral angle, "bad" if
 *   theta < 15 deg (slivers).
 *
 * Output 0 (vtkUnstructuredGrid): the mesh with its point data, plus cell data "G",
 * "MinAngle" (degrees) and "Inverted" (1 where the signed measure in input space is <= 0);
 * field data "G_min", "G_avg", "theta_min", "theta_avg", "pct_bad", "inverted",
 * "edges_in_unit_range" (% of edges whose metric length, divided by the median, is in
 * [1/sqrt2, sqrt2]), "NumberOfCells".
 *
 * Triangle surfaces in 3D also get the fidelity measures of the paper §6.3 (SurfaceFidelity on,
 * the default): field data "euler", "boundary_loops", "nonmanifold_edges", "components",
 * "self_intersections" (pairs of triangles that share no vertex and intersect). With the
 * optional input 1, the reference surface (the input surface the mesh was made from, e.g. the
 * output of vtkAnisoEmbedding), also "hausdorff" (sampled two-sided Hausdorff distance in % of
 * the reference's bounding-box diagonal), "hausdorff_to_input", "hausdorff_from_input" (each
 * direction, %), "flipped" (triangles whose normal points against the closest reference
 * triangle's), "input_euler", "input_boundary_loops", and cell data "Flipped". A reference on
 * a 2D domain or tetrahedral mesh is ignored with a warning.
 * Output 1 (vtkTable): histogram of the per-cell min angles, columns "MinAngle" (bin center,
 * degrees) and "Count", 5-degree bins over [0, 90) — shown as a bar chart in ParaView.
 *
 * Distributed runs (mpiexec pvbatch, pvserver): needs the whole mesh, so it asks its inputs
 * for the whole dataset and runs redundantly on every process that needs its output (the cost
 * is not divided); the whole result goes to piece 0 and the other pieces are empty, so that
 * gathering the pieces gives one copy. See Documentation/parallel.md.
 */
#ifndef vtkAnisoMeshQuality_h
#define vtkAnisoMeshQuality_h

#include "AnisoVoronoiFiltersQualityModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

namespace av
{
struct SimplexMesh;
}

class ANISOVORONOIFILTERSQUALITY_EXPORT vtkAnisoMeshQuality : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoMeshQuality* New();
  vtkTypeMacro(vtkAnisoMeshQuality, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Summary of the last run (also in the output's field data).
  vtkGetMacro(GMin, double);
  vtkGetMacro(GAvg, double);
  vtkGetMacro(ThetaMin, double);
  vtkGetMacro(ThetaAvg, double);
  vtkGetMacro(PercentBad, double);
  ///@}

  ///@{
  /// Surface fidelity measures for triangle surfaces (default on): topology,
  /// self-intersections and, with a reference surface on input 1, Hausdorff distance and
  /// flipped triangles.
  vtkSetMacro(SurfaceFidelity, bool);
  vtkGetMacro(SurfaceFidelity, bool);
  vtkBooleanMacro(SurfaceFidelity, bool);
  ///@}

  ///@{
  /// Sample points per triangle edge for the Hausdorff distance (>= 1, default 3: the
  /// barycentric grid of (n + 1)(n + 2) / 2 points on every triangle of both surfaces).
  vtkSetClampMacro(HausdorffSamplesPerEdge, int, 1, 64);
  vtkGetMacro(HausdorffSamplesPerEdge, int);
  ///@}

  /// The reference surface for the fidelity measures (optional input 1).
  void SetReferenceSurfaceConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(1, output);
  }
  void SetReferenceSurfaceData(vtkDataObject* data) { this->SetInputData(1, data); }

  ///@{
  /// Fidelity summary of the last run (-1 when not computed).
  vtkGetMacro(HausdorffPercent, double);
  vtkGetMacro(NumberOfSelfIntersections, vtkIdType);
  vtkGetMacro(NumberOfFlipped, vtkIdType);
  ///@}

protected:
  vtkAnisoMeshQuality();
  ~vtkAnisoMeshQuality() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The surface fidelity measures into `output` (triangle surfaces only); false on error.
  bool RunSurfaceFidelity(const av::SimplexMesh& mesh,
    vtkInformationVector** inputVector,
    vtkUnstructuredGrid* output);

  double GMin = 0.0;
  double GAvg = 0.0;
  double ThetaMin = 0.0;
  double ThetaAvg = 0.0;
  double PercentBad = 0.0;
  bool SurfaceFidelity = true;
  int HausdorffSamplesPerEdge = 3;
  double HausdorffPercent = -1.0;
  vtkIdType NumberOfSelfIntersections = -1;
  vtkIdType NumberOfFlipped = -1;

private:
  vtkAnisoMeshQuality(const vtkAnisoMeshQuality&) = delete;
  void operator=(const vtkAnisoMeshQuality&) = delete;
};

#endif
