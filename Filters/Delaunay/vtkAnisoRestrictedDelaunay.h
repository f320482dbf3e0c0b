// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoRestrictedDelaunay
 * @brief The anisotropic mesh: the dual (restricted Delaunay triangulation) of the restricted
 * Voronoi diagram of sites on the embedded mesh (paper §4.2), mapped back to the input space.
 *
 * The meshing itself is av::RunMeshingPipeline (Kernel/MeshingPipeline.h: RVD, RDT, site
 * improvement rounds, repair), shared with the CLI and the benchmark; this class converts the
 * inputs, maps its parameters to the pipeline's options and builds the output.
 *
 * Inputs as vtkAnisoRestrictedVoronoi: port 0 the embedded mesh (embedding point array chosen
 * with SetInputArrayToProcess(0, ...), default "Embedding"), port 1 the sites (output of
 * vtkAnisoParticleSampler, or any points inside the mesh).
 *
 * Output (vtkUnstructuredGrid): one triangle (tetrahedron) per Voronoi vertex where 3 (4)
 * restricted cells meet inside the domain. Its points are the sites in input space, in site
 * order, then the sites inserted by the repair, with the sites' point data (e.g. "Metric",
 * "Embedding"; for inserted sites "CellId" / "Barycentric" are theirs and every other array
 * that port 0 also has as point data is interpolated linearly from the mesh, others are 0),
 * plus "InsertedSite" (1 for inserted sites). Sites that no cell uses stay as unreferenced
 * points. Cell data "Inverted" (1 where the back-projected element is inverted or flat in
 * input space). Field data "NumInverted", "NumNonManifoldFaces" (both after the repair),
 * "NumOpenInteriorFaces", "NumUnusedSites", "NumInsertedSites", "RepairRounds",
 * "NumInvertedBeforeRepair", "NumNonManifoldFacesBeforeRepair", "RepairSeconds" (the rounds
 * after the first diagram), "DelaunaySeconds" (everything, repair included).
 *
 * Repair (paper §4.2, RepairInverted, default on): while an element is inverted, one site is
 * inserted at the Voronoi vertex dual to each inverted element (its circumcenter in the
 * embedding, restricted to the domain) and the diagram recomputed, at most MaxRepairRounds
 * times (default 10). RepairNonManifold (default on) also repairs faces shared by more than
 * two elements. What remains is reported with a warning. A volume dual still invalid then
 * (inverted or flat elements, faces of more than two) is replaced, with ValidDual (default on),
 * by a mesh of the same sites that is valid by construction (Delaunay tetrahedralization of the
 * sites, carved to the domain, flipped towards the metric's Delaunay criterion).
 *
 * Distributed runs (mpiexec pvbatch, pvserver): needs the whole mesh, so it asks its inputs
 * for the whole dataset and runs redundantly on every process that needs its output (the cost
 * is not divided); the whole result goes to piece 0 and the other pieces are empty, so that
 * gathering the pieces gives one copy. See Documentation/parallel.md.
 */
#ifndef vtkAnisoRestrictedDelaunay_h
#define vtkAnisoRestrictedDelaunay_h

#include "AnisoVoronoiFiltersDelaunayModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSDELAUNAY_EXPORT vtkAnisoRestrictedDelaunay : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoRestrictedDelaunay* New();
  vtkTypeMacro(vtkAnisoRestrictedDelaunay, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The sites (port 1); same as SetInputConnection(1, output).
  void SetSourceConnection(vtkAlgorithmOutput* output);

  ///@{
  /// Insert sites to repair inverted elements (default on).
  vtkSetMacro(RepairInverted, bool);
  vtkGetMacro(RepairInverted, bool);
  vtkBooleanMacro(RepairInverted, bool);
  ///@}

  ///@{
  /// Also repair faces shared by more than two elements (default off; only with
  /// RepairInverted). Inserts more sites, and on coarse input meshes may not converge.
  vtkSetMacro(RepairNonManifold, bool);
  vtkGetMacro(RepairNonManifold, bool);
  vtkBooleanMacro(RepairNonManifold, bool);
  /// Volumes: replace a dual that is still invalid after the repair by the Delaunay
  /// tetrahedralization of its sites, carved to the domain and flipped towards the metric's
  /// Delaunay criterion (valid by construction; default on; field data ValidDualReplaced).
  vtkSetMacro(ValidDual, bool);
  vtkGetMacro(ValidDual, bool);
  vtkBooleanMacro(ValidDual, bool);
  ///@}

  ///@{
  /// Site improvement rounds before the repair (default 1; 0 = the paper's pipeline; not in
  /// the paper). Each round moves the sites (walking on the embedded mesh) and recomputes the
  /// diagram once: OdtIterations ODT steps (every site whose cell does not meet the boundary
  /// moves to the volume-weighted mean of its dual simplices' circumcenters in the
  /// embedding), then the sites of every dual tetrahedron whose smallest dihedral angle in the
  /// embedding is below 15° are pushed apart along the sliver's flat direction.
  /// cube2 (5000 sites): G_avg 0.9025 -> 0.911, slivers 0.61 % -> 0.09 %.
  /// Moved sites get new positions and interpolated point data. Sites whose "FeatureKind"
  /// point array (written by vtkAnisoParticleSampler) is nonzero, the corner and feature-line
  /// sites, are never moved.
  vtkSetClampMacro(ImprovementRounds, int, 0, 10);
  vtkGetMacro(ImprovementRounds, int);
  ///@}

  ///@{
  /// ODT steps per improvement round (default 3, range 0..20; 0 = sliver pushes only). Steps
  /// after the first re-use the round's connectivity, so they cost no new diagram.
  vtkSetClampMacro(OdtIterations, int, 0, 20);
  vtkGetMacro(OdtIterations, int);
  ///@}

  ///@{
  /// Mesh improvement of the final mesh (default on; off = the paper's dual): 2-3 flips, edge
  /// removal and vertex smoothing that raise the worst element measured in the metric (input
  /// array 1 on port 0, default "Metric"; without it the step is skipped with a warning).
  /// Corner and feature-line vertices stay (the boundary: ImproveBoundary); nothing inverts. The mesh is then no
  /// longer the exact dual of the restricted Voronoi diagram; moved sites get interpolated
  /// point data.
  vtkSetMacro(ImproveMesh, bool);
  vtkGetMacro(ImproveMesh, bool);
  vtkBooleanMacro(ImproveMesh, bool);
  ///@}

  ///@{
  /// Mesh improvement on the boundary of tet meshes (default on): vertices of planar boundary
  /// patches move in their plane and boundary edges between coplanar faces are removed, both
  /// keeping the volume exactly; on smooth curved patches (faces within 10 degrees) the same
  /// flips run and vertices move onto the input's boundary surface, changing at most 0.1 % of
  /// the volume. Off: every boundary vertex and face stays.
  vtkSetMacro(ImproveBoundary, bool);
  vtkGetMacro(ImproveBoundary, bool);
  vtkBooleanMacro(ImproveBoundary, bool);
  ///@}

  ///@{
  /// Sweeps of the mesh improvement over all movable vertices after its worst-first passes
  /// (default 2, range 0..10; 0: none): each vertex moves where the mean §5.2 shape G of its
  /// star rises, never lowering the mesh's worst element or adding out-of-range edges.
  vtkSetClampMacro(MeanSmoothingSweeps, int, 0, 10);
  vtkGetMacro(MeanSmoothingSweeps, int);
  ///@}

  ///@{
  /// Surfaces: the ODT steps of the improvement rounds keep the corner and feature-line sites
  /// ("FeatureKind" != 0) where the sampler put them, on the creases (default off: they move
  /// like the others, and leave the creases). On fandisk it halves the distance to the input
  /// at the creases' corners; on other CAD parts it makes the dual less valid where the
  /// embedding is poor (Filters/Delaunay/README.md, "Feature sites on surfaces"). In volumes
  /// those sites stay anyway. Either way, on surfaces the edges between sites consecutive along
  /// a feature line are then flipped into the mesh (the feature lines at the sampler's
  /// "FeatureAngle", from the sites' field data; sites without it: none).
  vtkSetMacro(KeepFeatureSites, bool);
  vtkGetMacro(KeepFeatureSites, bool);
  vtkBooleanMacro(KeepFeatureSites, bool);
  ///@}

  ///@{
  /// Surfaces with an open boundary: a boundary vertex of the final mesh that is not on the
  /// input's boundary (a site just inside it whose cell reaches the boundary between two
  /// boundary sites, so the mesh's boundary cuts into the surface there) gets the triangle that
  /// closes that notch (default on; "NumBoundaryNotches", "NumBoundaryNotchesClosed" and
  /// "NumBoundaryNotchesLeft" in the field data).
  vtkSetMacro(CloseBoundaryNotches, bool);
  vtkGetMacro(CloseBoundaryNotches, bool);
  vtkBooleanMacro(CloseBoundaryNotches, bool);
  ///@}

  ///@{
  /// Insertion rounds at most (default 10, range 0..1000); each recomputes the diagram.
  vtkSetClampMacro(MaxRepairRounds, int, 0, 1000);
  vtkGetMacro(MaxRepairRounds, int);
  ///@}

  /// Counts of the last run (also in the output's field data); after the repair.
  vtkGetMacro(NumberOfInverted, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldFaces, vtkIdType);
  vtkGetMacro(NumberOfInsertedSites, vtkIdType);
  vtkGetMacro(NumberOfRepairRounds, int);

protected:
  vtkAnisoRestrictedDelaunay();
  ~vtkAnisoRestrictedDelaunay() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool RepairInverted = true;
  bool ImproveMesh = true;
  bool ImproveBoundary = true;
  int MeanSmoothingSweeps = 2;
  bool KeepFeatureSites = false;
  bool CloseBoundaryNotches = true;
  bool RepairNonManifold = true;
  bool ValidDual = true;
  int MaxRepairRounds = 10;
  int ImprovementRounds = 1;
  int OdtIterations = 3;

  vtkIdType NumberOfInverted = 0;
  vtkIdType NumberOfNonManifoldFaces = 0;
  vtkIdType NumberOfInsertedSites = 0;
  int NumberOfRepairRounds = 0;

private:
  vtkAnisoRestrictedDelaunay(const vtkAnisoRestrictedDelaunay&) = delete;
  void operator=(const vtkAnisoRestrictedDelaunay&) = delete;
};

#endif
