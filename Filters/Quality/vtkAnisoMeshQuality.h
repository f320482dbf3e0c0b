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

protected:
  vtkAnisoMeshQuality();
  ~vtkAnisoMeshQuality() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double GMin = 0.0;
  double GAvg = 0.0;
  double ThetaMin = 0.0;
  double ThetaAvg = 0.0;
  double PercentBad = 0.0;

private:
  vtkAnisoMeshQuality(const vtkAnisoMeshQuality&) = delete;
  void operator=(const vtkAnisoMeshQuality&) = delete;
};

#endif
