// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoAnisotropicMesh
 * @brief One-click anisotropic mesh of a tensor field ("Aniso Anisotropic Mesh" in ParaView):
 * the paper's pipeline up to the dual of the restricted Voronoi diagram, with its quality.
 *
 * Input and front part as vtkAnisoTensorPipeline (tensor or metric array chosen with
 * SetInputArrayToProcess; simplex split, tensor-to-metric, embedding, particle sampling with
 * NumberOfCells sites = mesh vertices), then vtkAnisoRestrictedDelaunay and
 * vtkAnisoMeshQuality.
 * Output 0 (vtkUnstructuredGrid): the triangles / tetrahedra, point data of the sites
 * ("Metric", "Embedding", ...), cell data "G", "MinAngle", "Inverted"; field data of the
 * quality (G_min, G_avg, theta_min, theta_avg, pct_bad, inverted, edges_in_unit_range,
 * NumberOfCells), of the dual (NumInverted, NumNonManifoldFaces, NumOpenInteriorFaces,
 * NumUnusedSites) and "L_avg", "L_max", "MetricScale". On triangle surfaces also the fidelity
 * measures of vtkAnisoMeshQuality against the mesh the embedding ran on (the input surface, or
 * the adapted background mesh): hausdorff, self_intersections, flipped (cell data "Flipped"),
 * euler, boundary_loops, input_euler, input_boundary_loops, nonmanifold_edges, components.
 * Output 1 (vtkTable): histogram of the per-cell min angles ("MinAngle" bin center, "Count").
 * Inverted elements are repaired by site insertion as in vtkAnisoRestrictedDelaunay
 * (RepairInverted, default on; MaxRepairRounds, default 10; RepairNonManifold, default on;
 * ValidDual, default on: a volume mesh still invalid is replaced by a valid one of its sites),
 * so the mesh may have more vertices than NumberOfCells; field data NumInsertedSites,
 * RepairRounds, NumInvertedBeforeRepair.
 */
#ifndef vtkAnisoAnisotropicMesh_h
#define vtkAnisoAnisotropicMesh_h

#include "AnisoVoronoiFiltersPipelinesModule.h" // export macro
#include "vtkAnisoTensorPipeline.h"

class ANISOVORONOIFILTERSPIPELINES_EXPORT vtkAnisoAnisotropicMesh : public vtkAnisoTensorPipeline
{
public:
  static vtkAnisoAnisotropicMesh* New();
  vtkTypeMacro(vtkAnisoAnisotropicMesh, vtkAnisoTensorPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Insert sites to repair inverted elements (default on).
  vtkSetMacro(RepairInverted, bool);
  vtkGetMacro(RepairInverted, bool);
  vtkBooleanMacro(RepairInverted, bool);
  ///@}

  ///@{
  /// Also repair faces shared by more than two elements (default off).
  vtkSetMacro(RepairNonManifold, bool);
  vtkGetMacro(RepairNonManifold, bool);
  vtkBooleanMacro(RepairNonManifold, bool);
  /// As vtkAnisoRestrictedDelaunay's ValidDual (default on).
  vtkSetMacro(ValidDual, bool);
  vtkGetMacro(ValidDual, bool);
  vtkBooleanMacro(ValidDual, bool);
  ///@}

  ///@{
  /// Insertion rounds at most (default 10, range 0..1000).
  vtkSetClampMacro(MaxRepairRounds, int, 0, 1000);
  vtkGetMacro(MaxRepairRounds, int);
  ///@}

  ///@{
  /// Site improvement rounds before the repair (default 2 here, 1 in vtkAnisoRestrictedDelaunay;
  /// 0 = the paper's pipeline) and ODT steps per round (default 3). Two rounds: the compressor
  /// of the README (result.frd) meshes with 0 inverted elements for seeds 1-5 (one round left
  /// 1 inverted element and a stalled repair at seed 1).
  vtkSetClampMacro(ImprovementRounds, int, 0, 10);
  vtkGetMacro(ImprovementRounds, int);
  vtkSetClampMacro(OdtIterations, int, 0, 20);
  vtkGetMacro(OdtIterations, int);
  ///@}

  ///@{
  /// Flips and vertex smoothing of the final mesh in the metric (default on; off = the
  /// paper's dual), as vtkAnisoRestrictedDelaunay::ImproveMesh.
  vtkSetMacro(ImproveMesh, bool);
  vtkGetMacro(ImproveMesh, bool);
  vtkBooleanMacro(ImproveMesh, bool);
  ///@}

  ///@{
  /// Surfaces: the crease and corner sites stay on their creases (default off), as
  /// vtkAnisoRestrictedDelaunay::KeepFeatureSites.
  vtkSetMacro(KeepFeatureSites, bool);
  vtkGetMacro(KeepFeatureSites, bool);
  vtkBooleanMacro(KeepFeatureSites, bool);
  ///@}

protected:
  vtkAnisoAnisotropicMesh();
  ~vtkAnisoAnisotropicMesh() override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestBackEnd(vtkUnstructuredGrid* embedded, vtkPolyData* sites, vtkTable* energy,
    vtkInformationVector* outputVector) override;
  const char* GetUserLabel() const override { return "Aniso Anisotropic Mesh"; }

  bool RepairInverted = true;
  bool RepairNonManifold = true;
  bool ValidDual = true;
  int MaxRepairRounds = 10;
  int ImprovementRounds = 2;
  int OdtIterations = 3;
  bool ImproveMesh = true;
  bool KeepFeatureSites = false;

private:
  vtkAnisoAnisotropicMesh(const vtkAnisoAnisotropicMesh&) = delete;
  void operator=(const vtkAnisoAnisotropicMesh&) = delete;
};

#endif
