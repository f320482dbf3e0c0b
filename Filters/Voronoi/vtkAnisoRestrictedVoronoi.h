// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoRestrictedVoronoi
 * @brief The restricted Voronoi diagram of sites in R^m̄ on the embedded mesh (paper §4.2),
 * drawn in the input space: anisotropic Voronoi cells.
 *
 * Input port 0: the embedded mesh (output of vtkAnisoEmbedding: triangles or tetrahedra with
 * an m̄-component embedding point array, chosen with SetInputArrayToProcess(0, 0, 0,
 * vtkDataObject::FIELD_ASSOCIATION_POINTS, name); default "Embedding").
 * Input port 1: the sites, a point set such as the output of vtkAnisoParticleSampler (point
 * arrays "CellId" and "Barycentric"). Without those arrays each point is located in the mesh
 * (input space) and its embedded position interpolated, so user-given points work too; a
 * point outside the mesh is an error.
 *
 * Every embedded element is clipped by the bisectors of the nearest sites in its own
 * barycentric coordinates (exact up to round-off), then mapped back by keeping the first m
 * coordinates.
 *
 * Output 0 (vtkUnstructuredGrid), in input space:
 * - volumes: one VTK_POLYHEDRON per site (MergeBySite on, default; the pieces of one site
 *   glued along element faces) or one per (Voronoi cell ∩ element) piece (MergeBySite off);
 * - 2D domains and surfaces: VTK_POLYGON, one per site when its pieces form one simple loop,
 *   else one per piece.
 * Cell data "SiteId", "Measure" (area / volume in input space of the drawn cell, so scaled
 * by ShrinkFactor^k), "EmbeddedMeasure" (in R^m̄, scaled the same way) and, only when some
 * cells are element pieces, "ElementId" (the input element of a piece; -1 for merged cells).
 * ShrinkFactor (default 1 = none) scales every cell about its vertex centroid (points are not
 * shared between cells), the usual way to show Voronoi cells (paper Fig. 15-18).
 *
 * Output 1 (vtkPolyData): the faces (volumes: polygons) or edges (2D: lines) of every output
 * cell, shrunk the same way, with cell data "SiteId", "FaceKind" (0 = bisector between two
 * cells, 1 = domain boundary, 2 = element face, only with MergeBySite off) and
 * "NeighborSiteId" (the other site of a bisector, else -1): color by FaceKind to tell the
 * boundary from the interior faces.
 *
 * Field data of both outputs: "TotalMeasure" (sum of the unshrunk cells), "DomainMeasure"
 * (measure of the input mesh), "RelativeVolumeError" (|Total - Domain| / Domain),
 * "NumberOfVoronoiCells" (non-empty sites), "NumberOfEmptySites", "VoronoiKernelSeconds" (the
 * clipping alone), "VoronoiSeconds" (the whole filter), "PieceNumber", "NumberOfPieces".
 *
 * Distributed runs (mpiexec pvbatch, pvserver): both inputs are requested whole (every
 * process gets the whole mesh and all sites); output piece p of n clips only the elements
 * [p*N/n, (p+1)*N/n) of the N mesh elements (TBB threads inside each process). With
 * MergeBySite off the pieces of all processes together are exactly the serial output. With
 * MergeBySite on, a Voronoi cell that straddles two element blocks comes out as one cell per
 * block. TotalMeasure, RelativeVolumeError and NumberOfVoronoiCells then describe this piece
 * only (DomainMeasure is always the whole mesh's). See Documentation/parallel.md.
 */
#ifndef vtkAnisoRestrictedVoronoi_h
#define vtkAnisoRestrictedVoronoi_h

#include "AnisoVoronoiFiltersVoronoiModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSVORONOI_EXPORT vtkAnisoRestrictedVoronoi : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoRestrictedVoronoi* New();
  vtkTypeMacro(vtkAnisoRestrictedVoronoi, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The sites (port 1); same as SetInputConnection(1, output).
  void SetSourceConnection(vtkAlgorithmOutput* output);

  ///@{
  /// One cell per site (default on) or one per (cell ∩ element) piece.
  vtkSetMacro(MergeBySite, bool);
  vtkGetMacro(MergeBySite, bool);
  vtkBooleanMacro(MergeBySite, bool);
  ///@}

  ///@{
  /// Scale each cell about its centroid by this factor (default 1 = no shrink; range 0.01..1).
  vtkSetClampMacro(ShrinkFactor, double, 0.01, 1.0);
  vtkGetMacro(ShrinkFactor, double);
  ///@}

  /// Figures of the last run (also in the output's field data).
  vtkGetMacro(TotalMeasure, double);
  vtkGetMacro(DomainMeasure, double);

protected:
  vtkAnisoRestrictedVoronoi();
  ~vtkAnisoRestrictedVoronoi() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool MergeBySite = true;
  double ShrinkFactor = 1.0;
  double TotalMeasure = 0.0;
  double DomainMeasure = 0.0;

private:
  vtkAnisoRestrictedVoronoi(const vtkAnisoRestrictedVoronoi&) = delete;
  void operator=(const vtkAnisoRestrictedVoronoi&) = delete;
};

#endif
