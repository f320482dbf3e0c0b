// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoDataConversion.h"

#include <vtkAlgorithm.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellLocator.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace vtkAnisoDataConversion
{

bool ToSimplexMesh(vtkDataSet* input, av::SimplexMesh& mesh, std::string& error, std::string* note)
{
  mesh = av::SimplexMesh();
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0)
  {
    error = "the input has no points or no cells";
    return false;
  }
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numCells = input->GetNumberOfCells();
  vtkIdType tris = 0, tets = 0, ignored = 0, other = 0;
  int otherType = -1;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    switch (input->GetCellType(c))
    {
      case VTK_TRIANGLE:
        ++tris;
        break;
      case VTK_TETRA:
        ++tets;
        break;
      case VTK_VERTEX:
      case VTK_POLY_VERTEX:
      case VTK_LINE:
      case VTK_POLY_LINE:
        ++ignored;
        break;
      default:
        ++other;
        otherType = input->GetCellType(c);
    }
  }
  if (other > 0)
  {
    std::ostringstream os;
    os << other << " cell(s) are not triangles or tetrahedra (first type: "
       << vtkCellTypes::GetClassNameFromTypeId(otherType)
       << "); apply 'Aniso Simplex Mesh' (vtkAnisoSimplexMesh) first to split them";
    error = os.str();
    return false;
  }
  if (tris > 0 && tets > 0)
  {
    error = "the input mixes triangles and tetrahedra; extract the volume (tetrahedra) or the "
            "surface (triangles) first";
    return false;
  }
  if (tris == 0 && tets == 0)
  {
    error = "the input has no triangle or tetrahedron";
    return false;
  }
  if (ignored > 0 && note)
  {
    std::ostringstream os;
    os << ignored << " vertex/line cell(s) were ignored";
    *note = os.str();
  }
  mesh.SimplexDim = tets > 0 ? 3 : 2;
  double bounds[6];
  input->GetBounds(bounds);
  const bool flat = mesh.SimplexDim == 2 && bounds[4] == bounds[5];
  mesh.AmbientDim = flat ? 2 : 3;
  mesh.Points.resize(static_cast<std::size_t>(numPoints) * mesh.AmbientDim);
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    for (int d = 0; d < mesh.AmbientDim; ++d)
    {
      if (!std::isfinite(p[d]))
      {
        std::ostringstream os;
        os << "point " << i << " has a non-finite coordinate";
        error = os.str();
        return false;
      }
      mesh.Points[static_cast<std::size_t>(i) * mesh.AmbientDim + d] = p[d];
    }
  }
  const int nv = mesh.SimplexDim + 1;
  mesh.Cells.reserve(static_cast<std::size_t>(mesh.SimplexDim == 3 ? tets : tris) * nv);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    const int type = input->GetCellType(c);
    if (type != VTK_TRIANGLE && type != VTK_TETRA)
    {
      continue;
    }
    input->GetCellPoints(c, ids);
    for (int k = 0; k < nv; ++k)
    {
      mesh.Cells.push_back(static_cast<std::int32_t>(ids->GetId(k)));
    }
  }
  return true;
}

vtkDataArray* FindPointTensorArray(vtkDataArray* chosen,
  int chosenAssociation,
  vtkDataSet* input,
  const char* fallbackName)
{
  if (!input)
    return nullptr;
  if (chosen)
  {
    return chosenAssociation == 0 ? chosen : nullptr; // points only
  }
  if (vtkDataArray* tensors = input->GetPointData()->GetTensors())
    return tensors;
  return fallbackName ? input->GetPointData()->GetArray(fallbackName) : nullptr;
}

bool ToMetricField(vtkDataArray* array,
  std::size_t numPoints,
  av::MetricField& metric,
  std::string& error)
{
  if (!array)
  {
    error = "no metric/tensor array was found (choose one with SetInputArrayToProcess)";
    return false;
  }
  const int nc = array->GetNumberOfComponents();
  if (nc != 6 && nc != 9)
  {
    std::ostringstream os;
    os << "array '" << (array->GetName() ? array->GetName() : "") << "' has " << nc
       << " components; a symmetric tensor needs 6 (XX,YY,ZZ,XY,YZ,XZ) or 9";
    error = os.str();
    return false;
  }
  if (static_cast<std::size_t>(array->GetNumberOfTuples()) != numPoints)
  {
    std::ostringstream os;
    os << "array '" << (array->GetName() ? array->GetName() : "") << "' has "
       << array->GetNumberOfTuples() << " tuples but the mesh has " << numPoints << " points";
    error = os.str();
    return false;
  }
  metric.Values.resize(numPoints * 6);
  double t[9];
  for (std::size_t i = 0; i < numPoints; ++i)
  {
    array->GetTuple(static_cast<vtkIdType>(i), t);
    double* m = metric.Values.data() + 6 * i;
    if (nc == 6)
    {
      for (int k = 0; k < 6; ++k)
        m[k] = t[k];
    }
    else
    {
      // 9 components, row-major; VTK 6-component order XX,YY,ZZ,XY,YZ,XZ.
      m[0] = t[0];
      m[1] = t[4];
      m[2] = t[8];
      m[3] = 0.5 * (t[1] + t[3]);
      m[4] = 0.5 * (t[5] + t[7]);
      m[5] = 0.5 * (t[2] + t[6]);
    }
    for (int k = 0; k < 6; ++k)
    {
      if (!std::isfinite(m[k]))
      {
        std::ostringstream os;
        os << "array '" << (array->GetName() ? array->GetName() : "")
           << "' has a NaN/Inf value at point " << i;
        error = os.str();
        return false;
      }
    }
  }
  return true;
}

bool ToEmbedding(vtkDataArray* array,
  const av::SimplexMesh& mesh,
  av::Embedding& embedding,
  std::string& error)
{
  if (!array)
  {
    error = "no embedding array was found (run the embedding filter first, or choose the "
            "array with SetInputArrayToProcess)";
    return false;
  }
  const int dim = array->GetNumberOfComponents();
  if (dim <= mesh.AmbientDim || dim > 64)
  {
    std::ostringstream os;
    os << "embedding array '" << (array->GetName() ? array->GetName() : "") << "' has " << dim
       << " components; expected more than the input dimension " << mesh.AmbientDim;
    error = os.str();
    return false;
  }
  const std::size_t n = mesh.NumPoints();
  if (static_cast<std::size_t>(array->GetNumberOfTuples()) != n)
  {
    std::ostringstream os;
    os << "embedding array has " << array->GetNumberOfTuples() << " tuples but the mesh has " << n
       << " points";
    error = os.str();
    return false;
  }
  embedding.Dim = dim;
  embedding.Coords.resize(n * dim);
  double scale = 0;
  for (double v : mesh.Points)
    scale = std::max(scale, std::abs(v));
  const double tol = 1e-6 * std::max(1.0, scale);
  for (std::size_t i = 0; i < n; ++i)
  {
    double* x = embedding.Coords.data() + i * dim;
    array->GetTuple(static_cast<vtkIdType>(i), x);
    for (int d = 0; d < dim; ++d)
    {
      if (!std::isfinite(x[d]))
      {
        std::ostringstream os;
        os << "embedding has a NaN/Inf value at point " << i;
        error = os.str();
        return false;
      }
    }
    for (int d = 0; d < mesh.AmbientDim; ++d)
    {
      if (std::abs(x[d] - mesh.Points[i * mesh.AmbientDim + d]) > tol)
      {
        std::ostringstream os;
        os << "embedding array does not belong to this mesh: its first " << mesh.AmbientDim
           << " coordinates differ from the point coordinates at point " << i;
        error = os.str();
        return false;
      }
    }
  }
  return true;
}

namespace
{
/// Sites without CellId / Barycentric: each point located in `meshData` (input space), in
/// the cell where it is most inside; false with `error` for a point outside the mesh.
bool LocateSites(vtkDataSet* sites,
  vtkDataSet* meshData,
  int nv,
  av::SiteSet& out,
  std::string& error)
{
  const vtkIdType n = sites->GetNumberOfPoints();
  // vtk cell id -> simplex index (ToSimplexMesh skips vertex/line cells).
  std::vector<std::int32_t> simplexOf(static_cast<std::size_t>(meshData->GetNumberOfCells()), -1);
  std::int32_t next = 0;
  for (vtkIdType c = 0; c < meshData->GetNumberOfCells(); ++c)
  {
    const int type = meshData->GetCellType(c);
    if (type == VTK_TRIANGLE || type == VTK_TETRA)
      simplexOf[c] = next++;
  }
  vtkNew<vtkCellLocator> locator;
  locator->SetDataSet(meshData);
  locator->BuildLocator();
  const double diag = std::max(meshData->GetLength(), 1e-300);
  const double tol = 1e-6 * diag;
  vtkNew<vtkGenericCell> cell;
  vtkNew<vtkIdList> candidates;
  double pcoords[3], weights[8], best[8], closest[3], dist2;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    sites->GetPoint(i, x);
    // VTK's cells accept points slightly outside (parametric tolerance): among the cells
    // near x keep the one where x is most inside (largest smallest weight), so that a point
    // on a shared face does not get the neighbor's clamped weights.
    double box[6] = { x[0] - tol, x[0] + tol, x[1] - tol, x[1] + tol, x[2] - tol, x[2] + tol };
    locator->FindCellsWithinBounds(box, candidates);
    vtkIdType cid = -1;
    double bestMin = -std::numeric_limits<double>::infinity();
    for (vtkIdType k = 0; k < candidates->GetNumberOfIds(); ++k)
    {
      const vtkIdType c = candidates->GetId(k);
      if (simplexOf[c] < 0)
        continue;
      meshData->GetCell(c, cell);
      int subId = 0;
      if (cell->EvaluatePosition(x, closest, subId, pcoords, dist2, weights) < 0 ||
        dist2 > tol * tol)
        continue;
      double wmin = weights[0];
      for (int a = 1; a < nv; ++a)
        wmin = std::min(wmin, weights[a]);
      if (wmin > bestMin)
      {
        bestMin = wmin;
        cid = c;
        std::copy(weights, weights + nv, best);
      }
    }
    // A point outside every cell by more than round-off is outside the mesh.
    if (cid >= 0 && bestMin < -1e-6)
      cid = -1;
    if (cid < 0 || simplexOf[cid] < 0)
    {
      std::ostringstream os;
      os << "site " << i << " at (" << x[0] << ", " << x[1] << ", " << x[2]
         << ") is outside the mesh; give sites inside the domain or the CellId/Barycentric "
            "arrays of the particle sampler";
      error = os.str();
      return false;
    }
    std::copy(best, best + nv, weights);
    out.CellIds[i] = simplexOf[cid];
    // Clamp round-off and renormalize: the kernels require weights >= 0 summing to 1.
    double sum = 0.0;
    for (int a = 0; a < nv; ++a)
      sum += (weights[a] = std::max(0.0, weights[a]));
    for (int a = 0; a < nv; ++a)
      out.Bary[4 * i + a] = weights[a] / sum;
  }
  return true;
}

/// Embedded position of every site: barycentric combination of its cell's embedded vertices.
bool EmbedSites(const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  av::SiteSet& out,
  std::string& error)
{
  const int nv = mesh.VerticesPerCell();
  const auto n = static_cast<vtkIdType>(out.CellIds.size());
  const int dim = embedding.Dim;
  out.Coords.assign(static_cast<std::size_t>(n) * dim, 0.0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const std::int32_t* c = mesh.Cell(out.CellIds[i]);
    double* x = out.Coords.data() + i * dim;
    for (int a = 0; a < nv; ++a)
    {
      const double w = out.Bary[4 * i + a];
      if (!std::isfinite(w))
      {
        std::ostringstream os;
        os << "site " << i << " has a NaN/Inf barycentric coordinate";
        error = os.str();
        return false;
      }
      const double* e = embedding.At(c[a]);
      for (int d = 0; d < dim; ++d)
        x[d] += w * e[d];
    }
  }
  return true;
}
} // namespace

bool ToSiteSet(vtkDataSet* sites,
  vtkDataSet* meshData,
  const av::SimplexMesh& mesh,
  const av::Embedding& embedding,
  av::SiteSet& out,
  std::string& error,
  std::string* note)
{
  out = av::SiteSet();
  out.Dim = embedding.Dim;
  const vtkIdType n = sites ? sites->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    error = "the sites input has no points";
    return false;
  }
  const int nv = mesh.VerticesPerCell();
  const auto numCells = static_cast<vtkIdType>(mesh.NumCells());
  out.CellIds.resize(static_cast<std::size_t>(n));
  out.Bary.assign(static_cast<std::size_t>(n) * 4, 0.0);
  vtkDataArray* cellIds = sites->GetPointData()->GetArray("CellId");
  vtkDataArray* bary = sites->GetPointData()->GetArray("Barycentric");
  const bool given =
    cellIds && bary && cellIds->GetNumberOfComponents() == 1 && bary->GetNumberOfComponents() == 4;
  if (given)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double c = cellIds->GetComponent(i, 0);
      if (!(c >= 0 && c < static_cast<double>(numCells)))
      {
        std::ostringstream os;
        os << "site " << i << " has CellId " << c << " but the mesh has " << numCells
           << " cells: the sites were not sampled on this mesh";
        error = os.str();
        return false;
      }
      out.CellIds[i] = static_cast<std::int32_t>(c);
      bary->GetTuple(i, out.Bary.data() + 4 * i);
    }
  }
  else
  {
    if (!meshData)
    {
      error = "the sites have no CellId/Barycentric arrays and no mesh to locate them in";
      return false;
    }
    if (!LocateSites(sites, meshData, nv, out, error))
    {
      return false;
    }
    if (note)
      *note = "the sites have no CellId/Barycentric arrays: located them in the mesh";
  }
  return EmbedSites(mesh, embedding, out, error);
}

vtkSmartPointer<vtkUnstructuredGrid> FromSimplexMesh(const av::SimplexMesh& mesh)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  const std::size_t n = mesh.NumPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n));
  for (std::size_t i = 0; i < n; ++i)
  {
    const double* p = mesh.Point(i);
    points->SetPoint(static_cast<vtkIdType>(i), p[0], p[1], mesh.AmbientDim == 3 ? p[2] : 0.0);
  }
  grid->SetPoints(points);
  const int nv = mesh.VerticesPerCell();
  const int type = mesh.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE;
  grid->AllocateExact(static_cast<vtkIdType>(mesh.NumCells()), nv);
  vtkIdType ids[4];
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const std::int32_t* cell = mesh.Cell(c);
    for (int k = 0; k < nv; ++k)
      ids[k] = cell[k];
    grid->InsertNextCell(type, nv, ids);
  }
  return grid;
}

bool ToVoronoiInputs(vtkDataSet* meshInput,
  vtkDataArray* embeddingArray,
  vtkDataSet* sitesInput,
  av::SimplexMesh& mesh,
  av::Embedding& embedding,
  av::SiteSet& sites,
  std::string& error,
  std::string* note)
{
  if (!ToSimplexMesh(meshInput, mesh, error, note) ||
    !ToEmbedding(embeddingArray, mesh, embedding, error))
  {
    return false;
  }
  if (!ToSiteSet(sitesInput, meshInput, mesh, embedding, sites, error))
  {
    error = "Sites: " + error;
    return false;
  }
  return true;
}

vtkSmartPointer<vtkDataArray> MakeArray(const char* name,
  const double* values,
  std::size_t tuples,
  int components)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  std::copy(values, values + tuples * components, array->GetPointer(0));
  return array;
}

vtkSmartPointer<vtkDataArray> MakeIntArray(const char* name,
  const std::vector<std::int32_t>& values)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  return array;
}

void AddFeatureFieldData(vtkFieldData* fd,
  const std::vector<std::int32_t>& edges,
  const std::vector<std::int32_t>& corners)
{
  vtkNew<vtkIdTypeArray> e;
  e->SetName("FeatureEdges");
  e->SetNumberOfComponents(2);
  e->SetNumberOfTuples(static_cast<vtkIdType>(edges.size() / 2));
  for (std::size_t i = 0; i + 1 < edges.size(); i += 2)
  {
    e->SetValue(static_cast<vtkIdType>(i), edges[i]);
    e->SetValue(static_cast<vtkIdType>(i + 1), edges[i + 1]);
  }
  vtkNew<vtkIdTypeArray> c;
  c->SetName("FeatureCorners");
  c->SetNumberOfTuples(static_cast<vtkIdType>(corners.size()));
  for (std::size_t i = 0; i < corners.size(); ++i)
    c->SetValue(static_cast<vtkIdType>(i), corners[i]);
  fd->AddArray(e);
  fd->AddArray(c);
}

bool FeatureFieldData(vtkFieldData* fd,
  std::vector<std::int32_t>& edges,
  std::vector<std::int32_t>& corners,
  bool& found,
  std::string& error)
{
  found = false;
  edges.clear();
  corners.clear();
  vtkDataArray* e = fd ? fd->GetArray("FeatureEdges") : nullptr;
  vtkDataArray* c = fd ? fd->GetArray("FeatureCorners") : nullptr;
  if (!e && !c)
    return true;
  if ((e && e->GetNumberOfComponents() != 2) || (c && c->GetNumberOfComponents() != 1))
  {
    error = "field data: FeatureEdges must have 2 components and FeatureCorners 1";
    return false;
  }
  const auto id = [&](double v, std::int32_t& out)
  {
    if (!(v >= 0.0 && v < 2147483647.0) || v != std::floor(v))
    {
      error = "field data: FeatureEdges / FeatureCorners hold a value that is not a point id";
      return false;
    }
    out = static_cast<std::int32_t>(v);
    return true;
  };
  for (vtkIdType i = 0; e && i < e->GetNumberOfTuples(); ++i)
    for (int k = 0; k < 2; ++k)
    {
      std::int32_t v = 0;
      if (!id(e->GetComponent(i, k), v))
        return false;
      edges.push_back(v);
    }
  for (vtkIdType i = 0; c && i < c->GetNumberOfTuples(); ++i)
  {
    std::int32_t v = 0;
    if (!id(c->GetTuple1(i), v))
      return false;
    corners.push_back(v);
  }
  found = true;
  return true;
}

void RemoveFeatureFieldData(vtkFieldData* fd)
{
  if (!fd)
    return;
  fd->RemoveArray("FeatureEdges");
  fd->RemoveArray("FeatureCorners");
}

void RequestWholeInputs(vtkInformationVector** inputVector, int numberOfInputPorts)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  for (int port = 0; port < numberOfInputPorts; ++port)
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
    {
      vtkInformation* info = inputVector[port]->GetInformationObject(i);
      info->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
      info->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
      info->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
}

void RequestedPiece(vtkInformation* request,
  vtkInformationVector* outputVector,
  int& piece,
  int& numberOfPieces)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  piece = 0;
  numberOfPieces = 1;
  int port = request && request->Has(vtkExecutive::FROM_OUTPUT_PORT())
    ? request->Get(vtkExecutive::FROM_OUTPUT_PORT())
    : 0;
  if (port < 0 || port >= outputVector->GetNumberOfInformationObjects())
    port = 0;
  vtkInformation* info = outputVector->GetInformationObject(port);
  if (!info || !info->Has(SDDP::UPDATE_PIECE_NUMBER()) ||
    !info->Has(SDDP::UPDATE_NUMBER_OF_PIECES()))
    return;
  numberOfPieces = std::max(1, info->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
  piece = std::min(std::max(0, info->Get(SDDP::UPDATE_PIECE_NUMBER())), numberOfPieces - 1);
}

bool IsSecondaryPiece(vtkInformation* request, vtkInformationVector* outputVector)
{
  int piece = 0, pieces = 1;
  RequestedPiece(request, outputVector, piece, pieces);
  return piece > 0;
}

bool NothingToCompute(
  vtkInformation* request, vtkInformationVector* outputVector, vtkDataSet* input)
{
  return IsSecondaryPiece(request, outputVector) || !input || input->GetNumberOfPoints() == 0 ||
    input->GetNumberOfCells() == 0;
}

bool IsSurfaceInThreeD(vtkDataSet* data)
{
  if (!data || data->GetNumberOfCells() == 0 || data->GetCellType(0) != VTK_TRIANGLE)
    return false;
  double bounds[6];
  data->GetBounds(bounds);
  return bounds[5] > bounds[4];
}

void CopySimplicesWithInputData(
  vtkDataSet* input, const av::SimplexMesh& mesh, vtkUnstructuredGrid* output)
{
  output->ShallowCopy(vtkAnisoDataConversion::FromSimplexMesh(mesh));
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
    pts->SetPoint(i, input->GetPoint(i));
  output->SetPoints(pts);
  output->GetPointData()->ShallowCopy(input->GetPointData());
  if (static_cast<std::size_t>(input->GetNumberOfCells()) == mesh.NumCells())
  {
    output->GetCellData()->ShallowCopy(input->GetCellData());
  }
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
}
}
