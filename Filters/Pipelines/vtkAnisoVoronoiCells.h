// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoVoronoiCells
 * @brief One-click anisotropic Voronoi cells of a tensor field ("Aniso Anisotropic Voronoi"
 * in ParaView): the whole pipeline of the paper, drawn as shrunken cells.
 *
 * Input and front part as vtkAnisoTensorPipeline (tensor or metric array chosen with
 * SetInputArrayToProcess; simplex split, tensor-to-metric, embedding, particle sampling with
 * NumberOfCells sites), then vtkAnisoRestrictedVoronoi with ShrinkFactor.
 * Output 0 (vtkUnstructuredGrid): one shrunken polyhedron (volume) or polygon (2D domain,
 * surface) per site, cell data "SiteId", "Measure", "EmbeddedMeasure" and
 * "Stretch" = sqrt(λmax / λmin) of the metric at the cell's site (a zero eigenvalue of a 2D /
 * surface metric is ignored).
 * Output 1 (vtkPolyData): the faces (edges in 2D) with "SiteId", "FaceKind", "NeighborSiteId"
 * and "Stretch" (of their cell).
 * Output 2 (vtkTable): the embedding energy per iteration (Iteration, E_em, E_reg, E_total).
 * Field data of outputs 0 and 1: the restricted Voronoi figures (TotalMeasure, DomainMeasure,
 * RelativeVolumeError, NumberOfVoronoiCells, ...) plus "L_avg", "L_max" (embedding edge
 * length errors, %) and "MetricScale".
 * Parameters (defaults): NumberOfCells (2000), TargetDimension (8), Iterations (50),
 * SamplingIterations (150), SamplingWarmupIterations (100), PreserveSharpFeatures (on),
 * FeatureAngle (30), MaximumAnisotropy (10), MinimumEigenvalue (0.1), SmoothingIterations
 * (10), ShrinkFactor (0.8), Seed (1), FieldMode (AUTOMATIC).
 */
#ifndef vtkAnisoVoronoiCells_h
#define vtkAnisoVoronoiCells_h

#include "AnisoVoronoiFiltersPipelinesModule.h" // export macro
#include "vtkAnisoTensorPipeline.h"

class ANISOVORONOIFILTERSPIPELINES_EXPORT vtkAnisoVoronoiCells : public vtkAnisoTensorPipeline
{
public:
  static vtkAnisoVoronoiCells* New();
  vtkTypeMacro(vtkAnisoVoronoiCells, vtkAnisoTensorPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Scale of every cell about its centroid (default 0.8; 1 = no shrink).
  vtkSetClampMacro(ShrinkFactor, double, 0.01, 1.0);
  vtkGetMacro(ShrinkFactor, double);
  ///@}

protected:
  vtkAnisoVoronoiCells();
  ~vtkAnisoVoronoiCells() override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestBackEnd(vtkUnstructuredGrid* embedded, vtkPolyData* sites, vtkTable* energy,
    vtkInformationVector* outputVector) override;
  const char* GetUserLabel() const override { return "Aniso Anisotropic Voronoi"; }

  double ShrinkFactor = 0.8;

private:
  vtkAnisoVoronoiCells(const vtkAnisoVoronoiCells&) = delete;
  void operator=(const vtkAnisoVoronoiCells&) = delete;
};

#endif
