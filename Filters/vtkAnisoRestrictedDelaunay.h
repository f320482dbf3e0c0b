/**
 * @class vtkAnisoRestrictedDelaunay
 * @brief The anisotropic mesh: the dual (restricted Delaunay triangulation) of the restricted
 * Voronoi diagram of sites on the embedded mesh (paper §4.2), mapped back to the input space.
 *
 * Inputs as vtkAnisoRestrictedVoronoi: port 0 the embedded mesh (embedding point array chosen
 * with SetInputArrayToProcess(0, ...), default "Embedding"), port 1 the sites (output of
 * vtkAnisoParticleSampler, or any points inside the mesh).
 *
 * Output (vtkUnstructuredGrid): one triangle (tetrahedron) per Voronoi vertex where 3 (4)
 * restricted cells meet inside the domain. Its points are the sites in input space, in site
 * order, with the sites' point data (e.g. "Metric", "Embedding"); sites that no cell uses stay
 * as unreferenced points. Cell data "Inverted" (1 where the back-projected element is inverted
 * or flat in input space). Field data "NumInverted", "NumNonManifoldFaces",
 * "NumOpenInteriorFaces", "NumUnusedSites", "DelaunaySeconds".
 *
 * Nothing is repaired (the paper inserts points to fix inverted elements): the counts are
 * reported, with a warning when an element is inverted or a face non-manifold.
 *
 * Distributed runs (mpiexec pvbatch, pvserver): needs the whole mesh, so it asks its inputs
 * for the whole dataset and runs redundantly on every process that needs its output (the cost
 * is not divided); the whole result goes to piece 0 and the other pieces are empty, so that
 * gathering the pieces gives one copy. See Documentation/parallel.md.
 */
#ifndef vtkAnisoRestrictedDelaunay_h
#define vtkAnisoRestrictedDelaunay_h

#include "AnisoVoronoiFiltersModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

class ANISOVORONOIFILTERS_EXPORT vtkAnisoRestrictedDelaunay : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoRestrictedDelaunay* New();
  vtkTypeMacro(vtkAnisoRestrictedDelaunay, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The sites (port 1); same as SetInputConnection(1, output).
  void SetSourceConnection(vtkAlgorithmOutput* output);

  /// Counts of the last run (also in the output's field data).
  vtkGetMacro(NumberOfInverted, vtkIdType);
  vtkGetMacro(NumberOfNonManifoldFaces, vtkIdType);

protected:
  vtkAnisoRestrictedDelaunay();
  ~vtkAnisoRestrictedDelaunay() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType NumberOfInverted = 0;
  vtkIdType NumberOfNonManifoldFaces = 0;

private:
  vtkAnisoRestrictedDelaunay(const vtkAnisoRestrictedDelaunay&) = delete;
  void operator=(const vtkAnisoRestrictedDelaunay&) = delete;
};

#endif
