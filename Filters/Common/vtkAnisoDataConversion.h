// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkAnisoDataConversion.h
 * @brief Internal (not wrapped): conversions between VTK datasets and the VTK-free kernel
 * types (av::SimplexMesh, av::MetricField, av::Embedding).
 *
 * Every filter goes through these so that input checks (cell types, NaN, array sizes) are
 * written once. Functions return false and fill `error` with a message a user can act on.
 */
#ifndef vtkAnisoDataConversion_h
#define vtkAnisoDataConversion_h

#include "AnisoVoronoiFiltersCommonModule.h" // export macro
#include "SimplexMesh.h"                     // av:: kernel types

#include <cstdint>
#include <string>
#include <vector>
#include <vtkSmartPointer.h> // return values

class vtkAlgorithm;
class vtkInformation;
class vtkInformationVector;
class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkPointSet;
class vtkUnstructuredGrid;
class vtkPolyData;

namespace vtkAnisoDataConversion
{
/**
 * Extracts the simplicial mesh of `input`: all cells must be triangles or all tetrahedra
 * (lines/vertices are ignored with a warning text in `note`). A triangle mesh whose points
 * all have the same z is a flat 2D domain (AmbientDim 2); otherwise a surface (AmbientDim 3).
 */
ANISOVORONOIFILTERSCOMMON_EXPORT bool ToSimplexMesh(vtkDataSet* input,
  av::SimplexMesh& mesh,
  std::string& error,
  std::string* note = nullptr);

/**
 * The metric/tensor point array a filter works on: `chosen` (what GetInputArrayToProcess
 * returned, with its association; must be a point array), else the active point tensors, else the
 * point array `fallbackName`. Null when none exists.
 */
ANISOVORONOIFILTERSCOMMON_EXPORT vtkDataArray* FindPointTensorArray(vtkDataArray* chosen,
  int chosenAssociation,
  vtkDataSet* input,
  const char* fallbackName = "Metric");

/// Reads a 6-component (XX,YY,ZZ,XY,YZ,XZ) or 9-component symmetric tensor array into a
/// MetricField (values copied; NaN/Inf rejected). Only checks finiteness and size.
ANISOVORONOIFILTERSCOMMON_EXPORT bool ToMetricField(vtkDataArray* array,
  std::size_t numPoints,
  av::MetricField& metric,
  std::string& error);

/// Reads an embedding array (NumPoints x Dim, Dim >= AmbientDim) and checks that its first
/// AmbientDim columns match the mesh coordinates (the embedding keeps them fixed).
ANISOVORONOIFILTERSCOMMON_EXPORT bool ToEmbedding(vtkDataArray* array,
  const av::SimplexMesh& mesh,
  av::Embedding& embedding,
  std::string& error);

/**
 * Sites (particles) on the mesh from the points of `sites`: with point arrays "CellId" (index of
 * the containing triangle/tetrahedron in `mesh`) and "Barycentric" (4 components), as the
 * particle sampler writes them, the embedded position is the barycentric combination of the
 * cell's embedded vertices. Without them each point is located in `meshData` (input space,
 * vtkCellLocator) and its embedded position interpolated; a point outside the mesh is an error.
 */
ANISOVORONOIFILTERSCOMMON_EXPORT bool ToSiteSet(vtkDataSet* sites,
  vtkDataSet* meshData,
  const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  av::SiteSet& out,
  std::string& error,
  std::string* note = nullptr);

/// A vtkUnstructuredGrid of the mesh's triangles/tetrahedra (z = 0 for a flat 2D domain).
ANISOVORONOIFILTERSCOMMON_EXPORT vtkSmartPointer<vtkUnstructuredGrid> FromSimplexMesh(
  const av::SimplexMesh& mesh);

/**
 * The three inputs of the Voronoi/Delaunay filters at once: the embedded mesh, its embedding
 * array and the sites (ToSimplexMesh, ToEmbedding, ToSiteSet), with the error prefixed by the
 * input it concerns. A warning text about ignored cells goes to `note`.
 */
ANISOVORONOIFILTERSCOMMON_EXPORT bool ToVoronoiInputs(vtkDataSet* meshInput,
  vtkDataArray* embeddingArray,
  vtkDataSet* sitesInput,
  av::SimplexMesh& mesh,
  av::Embedding& embedding,
  av::SiteSet& sites,
  std::string& error,
  std::string* note = nullptr);

/// A vtkDoubleArray holding `values` (row-major, `components` per tuple).
ANISOVORONOIFILTERSCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeArray(const char* name,
  const double* values,
  std::size_t tuples,
  int components);

/**
 * `output` = the simplices of `mesh` (ToSimplexMesh of `input`) on the input's exact points,
 * with the input's point and field data, and its cell data when no cell was dropped.
 */
ANISOVORONOIFILTERSCOMMON_EXPORT void CopySimplicesWithInputData(
  vtkDataSet* input, const av::SimplexMesh& mesh, vtkUnstructuredGrid* output);

/// A vtkIntArray holding `values` (one component).
ANISOVORONOIFILTERSCOMMON_EXPORT vtkSmartPointer<vtkDataArray> MakeIntArray(const char* name,
  const std::vector<std::int32_t>& values);

/**
 * Feature lines as field data, the pipeline's one form for them: "FeatureEdges" (vtkIdTypeArray,
 * 2 components: the point ids of each feature edge) and "FeatureCorners" (1 component). The
 * Medit reader writes a file's Ridges and Corners so, the sampler the features it placed its
 * sites on. Filters that renumber points drop them (RemoveFeatureFieldData).
 */
ANISOVORONOIFILTERSCOMMON_EXPORT void AddFeatureFieldData(vtkFieldData* fd,
  const std::vector<std::int32_t>& edges,
  const std::vector<std::int32_t>& corners);
/// Reads them back: `found` false when there are none; false with `error` when malformed.
ANISOVORONOIFILTERSCOMMON_EXPORT bool FeatureFieldData(vtkFieldData* fd,
  std::vector<std::int32_t>& edges,
  std::vector<std::int32_t>& corners,
  bool& found,
  std::string& error);
/// Removes them (for outputs whose point ids are not the input's).
ANISOVORONOIFILTERSCOMMON_EXPORT void RemoveFeatureFieldData(vtkFieldData* fd);

/**
 * Distributed runs (mpiexec pvbatch, pvserver): asks every connection of every input port for
 * the whole dataset (piece 0 of 1, no ghost levels). For RequestUpdateExtent of filters that
 * need the whole mesh; each process then computes the same deterministic result.
 */
ANISOVORONOIFILTERSCOMMON_EXPORT void RequestWholeInputs(vtkInformationVector** inputVector,
  int numberOfInputPorts);

/// Piece and number of pieces requested on the output port that `request` came from (port 0
/// when unknown); 0 and 1 when no piece was requested.
ANISOVORONOIFILTERSCOMMON_EXPORT void RequestedPiece(vtkInformation* request,
  vtkInformationVector* outputVector,
  int& piece,
  int& numberOfPieces);

/// True when a whole-mesh filter has nothing to compute: another piece than 0 is asked for
/// (IsSecondaryPiece) or `input` is missing or has no point or no cell. Its output stays empty.
ANISOVORONOIFILTERSCOMMON_EXPORT bool NothingToCompute(
  vtkInformation* request, vtkInformationVector* outputVector, vtkDataSet* input);

/// True for a triangle mesh (first cell a triangle) that is not flat (its z varies): the
/// surface case of ToSimplexMesh, which gets the surface fidelity measures.
ANISOVORONOIFILTERSCOMMON_EXPORT bool IsSurfaceInThreeD(vtkDataSet* data);

/// True when a piece other than 0 of a split request is asked for: whole-mesh filters then
/// leave that output empty, so that gathering all pieces gives exactly one copy.
ANISOVORONOIFILTERSCOMMON_EXPORT bool IsSecondaryPiece(vtkInformation* request,
  vtkInformationVector* outputVector);
}

#endif
