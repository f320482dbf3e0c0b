// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoAdaptedBackgroundMesh
 * @brief The mesh the embedding runs on, adapted to the metric and to the number of sites:
 * long metric edges split, short ones collapsed (Kernel/MetricAdaptedMesh.h).
 *
 * Input: tetrahedra, 2D triangles (z = 0) or a triangle surface with a symmetric metric point
 * array (6 components XX, YY, ZZ, XY, YZ, XZ, or 9), chosen with
 * SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name); by default the
 * active point tensors, else "Metric". Split other cells first (vtkAnisoSimplexMesh).
 *
 * The metric is normalized to NumberOfSites (an output edge then has length about 1). Edges
 * longer than TargetEdgeLength (L_bg, default 1.5 output edges) are
 * split, longest first and conforming (every element through the edge is cut), so only the
 * stretched direction is refined; then edges shorter than CollapseRatio x L_bg are collapsed
 * where no element inverts or loses quality, the boundary, the feature lines (FeatureAngle) and
 * the corners keep their shape (within SurfaceDeviationAngle), the mesh stays a manifold and no
 * edge becomes longer than L_bg. The result's size follows the sites and the metric's
 * complexity, not the input's size.
 *
 * Output (vtkUnstructuredGrid): the adapted simplices. Point data: every input point array
 * carried with the parent weights (each new point is a barycentric combination of one input
 * element's vertices, so linear fields stay exact); the metric array itself is the
 * log-Euclidean interpolation (SPD). Cell data: the input cell arrays of each element's parent
 * cell, plus "ParentCellId". Field data: the input's, plus "BackgroundMetricScale" (s),
 * "BackgroundMaxEdgeLength", "BackgroundMeanEdgeLength" (normalized), "BackgroundSplits",
 * "BackgroundCollapses", "BackgroundInputPoints", "BackgroundSeconds", "BackgroundAdapted",
 * "BackgroundInputMeanEdgeLength". With OnlyWhenCoarse a mesh already finer than the output is
 * passed through (its own data and field data, "BackgroundAdapted" 0).
 *
 * Needs the whole mesh (asks for it in distributed runs; piece 0 gets the result).
 */
#ifndef vtkAnisoAdaptedBackgroundMesh_h
#define vtkAnisoAdaptedBackgroundMesh_h

#include "AnisoVoronoiFiltersBackgroundMeshModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERSBACKGROUNDMESH_EXPORT vtkAnisoAdaptedBackgroundMesh
  : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoAdaptedBackgroundMesh* New();
  vtkTypeMacro(vtkAnisoAdaptedBackgroundMesh, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Sites the output will have (default 2000): the metric is normalized to this count.
  vtkSetClampMacro(NumberOfSites, int, 1, 100000000);
  vtkGetMacro(NumberOfSites, int);
  ///@}

  ///@{
  /// L_bg: longest background edge, in output edges (default 1.5, range (0, 10]; 0.5 gives
  /// about 27x more points for little gain on real fields, Filters/BackgroundMesh/README.md).
  vtkSetClampMacro(TargetEdgeLength, double, 1e-3, 10.0);
  vtkGetMacro(TargetEdgeLength, double);
  ///@}

  ///@{
  /// Adapt only a mesh coarser than the output (its mean normalized edge longer than one output
  /// edge, av::CoarserThanOutput); a finer one passes through unchanged (default off: always
  /// adapt). Field data "BackgroundAdapted" (1 / 0) says which happened.
  vtkSetMacro(OnlyWhenCoarse, bool);
  vtkGetMacro(OnlyWhenCoarse, bool);
  vtkBooleanMacro(OnlyWhenCoarse, bool);
  ///@}

  ///@{
  /// Edges shorter than CollapseRatio x L_bg are collapsed when safe (default 0.4; 0 = none).
  vtkSetClampMacro(CollapseRatio, double, 0.0, 0.7);
  vtkGetMacro(CollapseRatio, double);
  ///@}

  ///@{
  /// Split long edges (default on) / collapse short ones (default on).
  vtkSetMacro(Refine, bool);
  vtkGetMacro(Refine, bool);
  vtkBooleanMacro(Refine, bool);
  vtkSetMacro(Coarsen, bool);
  vtkGetMacro(Coarsen, bool);
  vtkBooleanMacro(Coarsen, bool);
  ///@}

  ///@{
  /// Dihedral angle (degrees) above which an edge is a feature line kept by the collapses
  /// (default 30; 180 = no feature lines).
  vtkSetClampMacro(FeatureAngle, double, 1.0, 180.0);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /// How far (degrees) a collapse may turn a boundary face, surface triangle or line edge
  /// (default 1; 0 keeps the boundary exactly).
  vtkSetClampMacro(SurfaceDeviationAngle, double, 0.0, 30.0);
  vtkGetMacro(SurfaceDeviationAngle, double);
  ///@}

  ///@{
  /// Collapses keep every changed element's metric quality above min(this, the worst one they
  /// replace) (default 0.2).
  vtkSetClampMacro(MinimumQuality, double, 0.0, 0.99);
  vtkGetMacro(MinimumQuality, double);
  ///@}

  ///@{
  /// Refinement stops at this many points, with a warning (default 4,000,000).
  vtkSetClampMacro(MaximumNumberOfPoints, vtkIdType, 4, 2000000000);
  vtkGetMacro(MaximumNumberOfPoints, vtkIdType);
  ///@}

  ///@{
  /// Figures of the last run (also in the field data).
  vtkGetMacro(MetricScale, double);
  vtkGetMacro(MaxEdgeLength, double);
  vtkGetMacro(NumberOfSplits, vtkIdType);
  vtkGetMacro(NumberOfCollapses, vtkIdType);
  vtkGetMacro(Seconds, double);
  /// Whether the last run adapted the mesh (false: OnlyWhenCoarse and the input was fine).
  vtkGetMacro(Adapted, bool);
  /// The input's mean normalized edge length (output edges) in the last run.
  vtkGetMacro(InputMeanEdgeLength, double);
  ///@}

protected:
  vtkAnisoAdaptedBackgroundMesh();
  ~vtkAnisoAdaptedBackgroundMesh() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfSites = 2000;
  double TargetEdgeLength = 1.5;
  bool OnlyWhenCoarse = false;
  double CollapseRatio = 0.4;
  bool Refine = true;
  bool Coarsen = true;
  double FeatureAngle = 30.0;
  double SurfaceDeviationAngle = 1.0;
  double MinimumQuality = 0.2;
  vtkIdType MaximumNumberOfPoints = 4000000;
  double MetricScale = 1.0;
  double MaxEdgeLength = 0.0;
  vtkIdType NumberOfSplits = 0;
  vtkIdType NumberOfCollapses = 0;
  double Seconds = 0.0;
  bool Adapted = false;
  double InputMeanEdgeLength = 0.0;

private:
  vtkAnisoAdaptedBackgroundMesh(const vtkAnisoAdaptedBackgroundMesh&) = delete;
  void operator=(const vtkAnisoAdaptedBackgroundMesh&) = delete;
};

#endif
