// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoTensorToMetric.h"

#include "MetricAlgebra.h"
#include "MetricPreparation.h"
#include "SurfaceCurvatureMetric.h" // SurfaceVertexNormals
#include "TensorToMetric.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkAnisoTensorToMetric);

namespace
{
/// Unique point pairs joined by a cell edge, for any cell type (quadratic edges are chained
/// through their mid-edge nodes; 1D cells give consecutive pairs). Flat (a, b), a < b, sorted.
std::vector<std::int32_t> ExtractEdges(vtkDataSet* input)
{
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  vtkNew<vtkGenericCell> cell;
  std::vector<vtkIdType> chain;
  auto addChain = [&pairs](const std::vector<vtkIdType>& ids)
  {
    for (std::size_t k = 0; k + 1 < ids.size(); ++k)
    {
      auto a = static_cast<std::int32_t>(ids[k]);
      auto b = static_cast<std::int32_t>(ids[k + 1]);
      if (a != b)
        pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  };
  const vtkIdType numCells = input->GetNumberOfCells();
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    input->GetCell(c, cell);
    const int dim = cell->GetCellDimension();
    if (dim == 0)
      continue;
    vtkIdList* ids = cell->GetPointIds();
    if (dim == 1)
    {
      chain.clear();
      const vtkIdType n = ids->GetNumberOfIds();
      if (cell->GetCellType() == VTK_QUADRATIC_EDGE && n == 3)
        chain = { ids->GetId(0), ids->GetId(2), ids->GetId(1) };
      else
        for (vtkIdType k = 0; k < n; ++k)
          chain.push_back(ids->GetId(k));
      addChain(chain);
      continue;
    }
    for (int e = 0; e < cell->GetNumberOfEdges(); ++e)
    {
      vtkCell* edge = cell->GetEdge(e);
      vtkIdList* eids = edge->GetPointIds();
      const vtkIdType n = eids->GetNumberOfIds();
      if (n < 2)
        continue;
      // Higher-order edges: the two end points first, then the interior nodes in order.
      chain.clear();
      chain.push_back(eids->GetId(0));
      for (vtkIdType k = 2; k < n; ++k)
        chain.push_back(eids->GetId(k));
      chain.push_back(eids->GetId(1));
      addChain(chain);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::int32_t> flat;
  flat.reserve(2 * pairs.size());
  for (const auto& p : pairs)
  {
    flat.push_back(p.first);
    flat.push_back(p.second);
  }
  return flat;
}
/// The tensor tuples the kernel converts: point tensors as they are, or cell tensors averaged
/// to the points that cells use (`Used` maps tuples to points, `PointToTuple` back).
struct TensorTuples
{
  std::vector<double> Values;
  std::vector<vtkIdType> Used; // empty = every point, in order
  std::vector<std::int32_t> PointToTuple;
  vtkIdType Count = 0;
};

/// Averages the cell tensors to the points (NaN/Inf rejected with the cell id in `error`).
bool AverageCellTensors(vtkDataSet* input,
  vtkDataArray* tensors,
  const std::string& name,
  TensorTuples& out,
  std::string& error)
{
  const int nc = tensors->GetNumberOfComponents();
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numCells = input->GetNumberOfCells();
  std::vector<double> sum(static_cast<std::size_t>(numPoints) * nc, 0.0);
  std::vector<int> count(static_cast<std::size_t>(numPoints), 0);
  std::vector<double> t(nc);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    tensors->GetTuple(c, t.data());
    for (int k = 0; k < nc; ++k)
    {
      if (!std::isfinite(t[k]))
      {
        error =
          "tensor array '" + name + "' has a NaN or infinite value at cell " + std::to_string(c);
        return false;
      }
    }
    input->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      const vtkIdType p = ids->GetId(k);
      double* s = sum.data() + static_cast<std::size_t>(p) * nc;
      for (int j = 0; j < nc; ++j)
        s[j] += t[j];
      ++count[p];
    }
  }
  out.PointToTuple.assign(static_cast<std::size_t>(numPoints), -1);
  for (vtkIdType p = 0; p < numPoints; ++p)
  {
    if (count[p] == 0)
      continue;
    out.PointToTuple[p] = static_cast<std::int32_t>(out.Used.size());
    out.Used.push_back(p);
    const double* s = sum.data() + static_cast<std::size_t>(p) * nc;
    for (int j = 0; j < nc; ++j)
      out.Values.push_back(s[j] / count[p]);
  }
  out.Count = static_cast<vtkIdType>(out.Used.size());
  return true;
}

/**
 * The simplices the preparation integrates the complexity over: the tuples' points (every point,
 * or `pointToTuple`'s) and the cells of the highest dimension split by vtkCell::Triangulate.
 * False with `error` when the input has no 2D or 3D cell.
 */
bool BuildSimplices(vtkDataSet* input,
  const std::vector<std::int32_t>& pointToTuple,
  std::size_t count,
  av::SimplexMesh& mesh,
  std::string& error)
{
  vtkNew<vtkGenericCell> cell;
  int maxDim = 0;
  const vtkIdType numCells = input->GetNumberOfCells();
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    input->GetCell(c, cell);
    maxDim = std::max(maxDim, cell->GetCellDimension());
  }
  if (maxDim < 2)
  {
    error = "metric preparation needs 2D or 3D cells, the input has none (turn it off: "
            "Gradation off, NumberOfSites 0, SizeMode Tensor, no HMin/HMax)";
    return false;
  }
  mesh.AmbientDim = 3;
  mesh.SimplexDim = maxDim;
  mesh.Points.assign(3 * count, 0.0);
  auto tuple = [&pointToTuple](vtkIdType p)
  { return pointToTuple.empty() ? static_cast<std::int32_t>(p) : pointToTuple[p]; };
  for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
  {
    const std::int32_t t = tuple(p);
    if (t >= 0)
      input->GetPoint(p, mesh.Points.data() + 3 * static_cast<std::size_t>(t));
  }
  vtkNew<vtkIdList> ids;
  vtkNew<vtkPoints> points;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    input->GetCell(c, cell);
    if (cell->GetCellDimension() != maxDim || !cell->Triangulate(0, ids, points))
      continue;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      mesh.Cells.push_back(tuple(ids->GetId(k)));
  }
  mesh.Cells.resize(mesh.Cells.size() - mesh.Cells.size() % (maxDim + 1));
  return true;
}

/// Point array `name` of 6-component tuples (`used` maps tuples to points, as WriteOutput).
void AddPointTensors(vtkDataSet* output,
  const char* name,
  const std::vector<double>& values,
  const std::vector<vtkIdType>& used,
  int dimension)
{
  const vtkIdType numPoints = output->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(6);
  array->SetNumberOfTuples(numPoints);
  const double identity[6] = { 1, 1, dimension == 2 ? 0.0 : 1.0, 0, 0, 0 };
  if (used.empty())
  {
    std::copy(values.begin(), values.end(), array->GetPointer(0));
  }
  else
  {
    for (vtkIdType p = 0; p < numPoints; ++p)
      array->SetTypedTuple(p, identity);
    for (std::size_t k = 0; k < used.size(); ++k)
      array->SetTypedTuple(used[k], values.data() + 6 * k);
  }
  output->GetPointData()->AddArray(array);
}

}

vtkAnisoTensorToMetric::vtkAnisoTensorToMetric()
{
  this->SetMetricArrayName("Metric");
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::TENSORS);
}

vtkAnisoTensorToMetric::~vtkAnisoTensorToMetric()
{
  this->SetMetricArrayName(nullptr);
}

/// The tensor array: the chosen one, else the active point tensors, else the active cell
/// tensors. Null with `error` set when there is none or it is unusable.
vtkDataArray* vtkAnisoTensorToMetric::FindTensors(vtkInformationVector** inputVector,
  vtkDataSet* input,
  bool& cellTensors,
  std::string& error)
{
  int association = -1;
  vtkDataArray* tensors = this->GetInputArrayToProcess(0, inputVector, association);
  vtkInformation* arrayInfo = this->GetInputArrayInformation(0);
  if (!tensors && arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME()) &&
    arrayInfo->Get(vtkDataObject::FIELD_NAME()) && *arrayInfo->Get(vtkDataObject::FIELD_NAME()))
  {
    error = std::string("the input has no array named '") +
      arrayInfo->Get(vtkDataObject::FIELD_NAME()) + "'";
    return nullptr;
  }
  if (!tensors)
  {
    if ((tensors = input->GetPointData()->GetTensors()))
      association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    else if ((tensors = input->GetCellData()->GetTensors()))
      association = vtkDataObject::FIELD_ASSOCIATION_CELLS;
  }
  if (!tensors)
  {
    error = "no tensor array was found: choose one with SetInputArrayToProcess (ParaView: "
            "the 'Tensors' property) or make one the active point/cell tensors";
    return nullptr;
  }
  const std::string name = tensors->GetName() ? tensors->GetName() : "(unnamed)";
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    error = "tensor array '" + name + "' must be a point or a cell array";
    return nullptr;
  }
  const int nc = tensors->GetNumberOfComponents();
  if (nc != 6 && nc != 9)
  {
    error = "tensor array '" + name + "' has " + std::to_string(nc) +
      " components; expected 6 (symmetric, XX YY ZZ XY YZ XZ) or 9 (3x3, row-major)";
    return nullptr;
  }
  cellTensors = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  return tensors;
}

/// The kernel options from the filter's properties; false with `error` on a bad Dimension.
bool vtkAnisoTensorToMetric::BuildOptions(vtkDataSet* input,
  av::TensorToMetricOptions& options,
  std::string& error)
{
  options.Interpretation = this->Interpretation == TENSOR_AS_METRIC
    ? av::TensorInterpretation::TensorAsMetric
    : av::TensorInterpretation::EigenvaluesAsStretch;
  options.Eigenvalues = this->EigenvalueMode == CLAMP ? av::EigenvalueHandling::Clamp
                                                      : av::EigenvalueHandling::Absolute;
  options.MinimumEigenvalue = this->MinimumEigenvalue;
  options.MaximumAnisotropy = this->MaximumAnisotropy;
  options.SmoothingIterations = this->SmoothingIterations;
  options.ApplyGlobalScale = this->ApplyGlobalScale;
  if (this->Dimension == DIMENSION_AUTO)
  {
    double bounds[6];
    input->GetBounds(bounds);
    options.Dimension = bounds[4] == bounds[5] ? 2 : 3;
  }
  else if (this->Dimension == DIMENSION_2D || this->Dimension == DIMENSION_3D)
  {
    options.Dimension = this->Dimension;
  }
  else
  {
    error = "Dimension must be 0 (auto), 2 or 3, not " + std::to_string(this->Dimension);
    return false;
  }
  return true;
}

int vtkAnisoTensorToMetric::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* output = vtkDataSet::GetData(outputVector);
  if (!input || !output)
  {
    return 0;
  }
  output->ShallowCopy(input);
  const vtkIdType numPoints = input->GetNumberOfPoints();
  if (numPoints == 0)
  {
    return 1; // empty in, empty out
  }
  if (numPoints > std::numeric_limits<std::int32_t>::max())
  {
    vtkErrorMacro("too many points for 32-bit ids");
    return 0;
  }
  std::string error;
  bool cellTensors = false;
  vtkDataArray* tensors = this->FindTensors(inputVector, input, cellTensors, error);
  if (!tensors)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  const std::string name = tensors->GetName() ? tensors->GetName() : "(unnamed)";
  const int nc = tensors->GetNumberOfComponents();
  if (cellTensors && input->GetNumberOfCells() == 0)
  {
    return 1;
  }

  TensorTuples tuples;
  if (!cellTensors)
  {
    tuples.Count = numPoints;
    tuples.Values.resize(static_cast<std::size_t>(numPoints) * nc);
    for (vtkIdType i = 0; i < numPoints; ++i)
      tensors->GetTuple(i, tuples.Values.data() + static_cast<std::size_t>(i) * nc);
  }
  else if (!AverageCellTensors(input, tensors, name, tuples, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UpdateProgress(0.2);

  av::TensorToMetricOptions options;
  if (!this->BuildOptions(input, options, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UsedDimension = options.Dimension;

  std::vector<std::int32_t> edges;
  if (this->SmoothingIterations > 0 || (this->PreparationRequested() && this->Gradation))
  {
    edges = ExtractEdges(input);
    if (!tuples.PointToTuple.empty())
    {
      for (auto& e : edges)
        e = tuples.PointToTuple[e]; // edges come from cells, so every end point has a tuple
    }
    if (edges.empty() && options.SmoothingIterations > 0)
    {
      vtkWarningMacro("the input has no cell edges: smoothing skipped");
      options.SmoothingIterations = 0;
    }
  }
  this->UpdateProgress(0.3);

  // A triangle surface in 3D: the tensors' normal parts must not reach the metric.
  std::vector<double> normals;
  this->UsedTangentProjection = false;
  if (this->ProjectOntoSurface && options.Dimension == 3)
  {
    av::SimplexMesh surface;
    std::string ignored;
    if (vtkAnisoDataConversion::ToSimplexMesh(input, surface, ignored) &&
      surface.SimplexDim == 2 && surface.AmbientDim == 3)
    {
      if (!this->TupleNormals(surface, tuples.Used, normals, error))
      {
        vtkErrorMacro(<< error);
        return 0;
      }
      this->UsedTangentProjection = true;
    }
  }

  av::TensorToMetricResult result;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "tensor to metric conversion",
        [&]
        {
          try
          {
            result = this->UsedTangentProjection
              ? av::TangentTensorToMetric(tuples.Values.data(),
                  static_cast<std::size_t>(tuples.Count), nc, normals.data(), options)
              : av::TensorToMetric(tuples.Values.data(), static_cast<std::size_t>(tuples.Count),
                  nc, options, edges);
          }
          catch (const av::InputError& e)
          {
            throw av::InputError("tensor array '" + name + "': " + e.what());
          }
        }))
  {
    return 0;
  }
  this->UpdateProgress(0.9);

  // Round-off asymmetry is not worth a warning.
  if (result.MaxAsymmetry > 1e-10)
  {
    vtkWarningMacro("tensor array '" << name
                                     << "' is not symmetric (largest relative asymmetry |T - T^T| "
                                        "/ (2 |T|) = "
                                     << result.MaxAsymmetry
                                     << "); its symmetric part (T + T^T) / 2 was used");
  }
  this->MedianChange = this->Percentile95Change = this->ChangedFraction = 0.0;
  this->ImpliedSites = 0.0;
  this->NumberOfGradedPoints = 0;
  std::vector<double> rawMetric;
  if (this->PreparationRequested() &&
    !this->Prepare(input, tuples.PointToTuple, edges, options.Dimension, result, rawMetric))
  {
    return 0;
  }
  this->WriteOutput(result, tuples.Used, cellTensors, options.Dimension, output);
  if (!rawMetric.empty())
    AddPointTensors(output, "RawMetric", rawMetric, tuples.Used, options.Dimension);
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkAnisoTensorToMetric::PreparationRequested() const
{
  return this->Gradation || this->NumberOfSites > 0 || this->SizeMode != SIZE_FROM_TENSOR ||
    this->HMin > 0.0 || this->HMax > 0.0;
}

/// Runs av::PrepareMetric on the converted field: `result` gets the prepared metric, its
/// stretch and ranges, `rawMetric` the converted field at the same complexity; field figures
/// go to the members (WriteOutput adds them). False after vtkErrorMacro.
bool vtkAnisoTensorToMetric::Prepare(vtkDataSet* input,
  const std::vector<std::int32_t>& pointToTuple,
  const std::vector<std::int32_t>& edges,
  int dimension,
  av::TensorToMetricResult& result,
  std::vector<double>& rawMetric)
{
  av::SimplexMesh mesh;
  std::string error;
  if (!BuildSimplices(input, pointToTuple, result.Metric.NumPoints(), mesh, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  av::MetricPreparationOptions o;
  o.SizeMode = this->SizeMode == SIZE_UNIFORM ? av::MetricSizeMode::Uniform
    : this->SizeMode == SIZE_BLEND            ? av::MetricSizeMode::Blend
                                              : av::MetricSizeMode::Tensor;
  o.SizeBlend = this->SizeBlend;
  o.TargetSites = this->NumberOfSites;
  o.HMin = this->HMin;
  o.HMax = this->HMax;
  o.MinCellsAcross = this->MinCellsAcross;
  o.Gradation = this->Gradation;
  o.GradationFactor = this->GradationFactor;
  o.Dimension = dimension;
  av::MetricPreparationResult prep;
  if (!vtkAnisoFilterUtilities::RunKernel(
        this, "metric preparation", [&] { prep = av::PrepareMetric(mesh, result.Metric, o, edges); }))
  {
    return false;
  }
  // The raw field at the prepared one's complexity: the same number of cells.
  const double t = prep.RawComplexity > 0.0
    ? std::pow(prep.Complexity / prep.RawComplexity, 2.0 / mesh.SimplexDim)
    : 1.0;
  // With ApplyGlobalScale the normalization is undone at the end: the field keeps the scale the
  // embedding is tuned for (smallest eigenvalue 1 where nothing changed; a pure normalization
  // leaves the conversion's output as it was). "CellUnitScale" turns it into cell units.
  const double back = this->ApplyGlobalScale ? 1.0 / prep.Scale : 1.0;
  rawMetric = result.Metric.Values;
  for (double& v : rawMetric)
    v *= t * back;
  for (double& v : prep.Metric.Values)
    v *= back;
  result.Metric = std::move(prep.Metric);
  result.StretchRatio = std::move(prep.StretchRatio);
  result.GlobalScale *= prep.Scale * back;
  // Output units times CellUnitScale are cell units: the factor undone above, or 1.
  this->CellUnitScale = this->ApplyGlobalScale ? prep.Scale : 1.0;
  av::EigenvalueRange(result.Metric, dimension == 2, result.MinEigenvalue, result.MaxEigenvalue);
  const auto range = std::minmax_element(result.StretchRatio.begin(), result.StretchRatio.end());
  result.MinStretch = *range.first;
  result.MaxStretch = *range.second;
  this->MedianChange = prep.Deviation.Median;
  this->Percentile95Change = prep.Deviation.Percentile95;
  this->ChangedFraction = prep.Deviation.ChangedFraction;
  this->ImpliedSites = prep.ImpliedSites;
  this->NumberOfGradedPoints = static_cast<vtkIdType>(prep.NumGraded);
  const double figures[7] = { prep.Deviation.Maximum, prep.Complexity,
    static_cast<double>(prep.NumHMinClamped), static_cast<double>(prep.NumHMaxClamped),
    static_cast<double>(prep.GradationSweeps), prep.CellsAcross,
    static_cast<double>(prep.NumThicknessLimited) };
  std::copy(figures, figures + 7, this->PreparationFigures);
  return true;
}

/// Unit vertex normals of `surface` for the tuples (`used`: their point ids, empty = every point).
bool vtkAnisoTensorToMetric::TupleNormals(const av::SimplexMesh& surface,
  const std::vector<vtkIdType>& used, std::vector<double>& normals, std::string& error)
{
  std::vector<double> all;
  try
  {
    all = av::SurfaceVertexNormals(surface);
  }
  catch (const av::InputError& e)
  {
    error = std::string("tangent-plane projection: ") + e.what() +
      " (turn ProjectOntoSurface off to use the tensors as they are)";
    return false;
  }
  if (used.empty())
  {
    normals = std::move(all);
    return true;
  }
  normals.resize(3 * used.size());
  for (std::size_t k = 0; k < used.size(); ++k)
    std::copy_n(all.data() + 3 * used[k], 3, normals.data() + 3 * k);
  return true;
}

/// The Metric and Stretch point arrays and the field data of the conversion.
void vtkAnisoTensorToMetric::WriteOutput(const av::TensorToMetricResult& result,
  const std::vector<vtkIdType>& used,
  bool cellTensors,
  int dimension,
  vtkDataSet* output)
{
  const vtkIdType numPoints = output->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> metric;
  metric->SetName(this->MetricArrayName ? this->MetricArrayName : "Metric");
  metric->SetNumberOfComponents(6);
  metric->SetNumberOfTuples(numPoints);
  vtkNew<vtkDoubleArray> stretch;
  stretch->SetName("Stretch");
  stretch->SetNumberOfTuples(numPoints);
  if (used.empty() && !cellTensors)
  {
    std::copy(result.Metric.Values.begin(), result.Metric.Values.end(), metric->GetPointer(0));
    std::copy(result.StretchRatio.begin(), result.StretchRatio.end(), stretch->GetPointer(0));
  }
  else
  {
    // Points used by no cell: identity (the smallest eigenvalue after scaling is 1).
    const double identity2[6] = { 1, 1, 0, 0, 0, 0 };
    const double identity3[6] = { 1, 1, 1, 0, 0, 0 };
    for (vtkIdType p = 0; p < numPoints; ++p)
    {
      metric->SetTypedTuple(p, dimension == 2 ? identity2 : identity3);
      stretch->SetValue(p, 1.0);
    }
    for (std::size_t k = 0; k < used.size(); ++k)
    {
      metric->SetTypedTuple(used[k], result.Metric.At(k));
      stretch->SetValue(used[k], result.StretchRatio[k]);
    }
    if (used.size() < static_cast<std::size_t>(numPoints))
    {
      vtkWarningMacro(<< (numPoints - static_cast<vtkIdType>(used.size()))
                      << " point(s) are used by no cell: they got the identity metric");
    }
  }

  output->GetPointData()->AddArray(metric);
  output->GetPointData()->AddArray(stretch);
  output->GetPointData()->SetActiveTensors(metric->GetName());

  this->MetricScale = result.GlobalScale;
  this->MaxAsymmetry = result.MaxAsymmetry;
  this->NumberOfNegativeTuples = static_cast<vtkIdType>(result.NumNegative);
  this->NumberOfClampedTuples = static_cast<vtkIdType>(result.NumClamped);
  this->NumberOfCappedTuples = static_cast<vtkIdType>(result.NumCapped);
  this->StretchMin = result.MinStretch;
  this->StretchMax = result.MaxStretch;
  vtkFieldData* fd = output->GetFieldData();
  using vtkAnisoFilterUtilities::AddFieldValue;
  AddFieldValue(fd, "MetricScale", result.GlobalScale);
  AddFieldValue(fd, "MaxAsymmetry", result.MaxAsymmetry);
  AddFieldValue(fd, "NumNegative", static_cast<double>(result.NumNegative));
  AddFieldValue(fd, "NumClamped", static_cast<double>(result.NumClamped));
  AddFieldValue(fd, "NumCapped", static_cast<double>(result.NumCapped));
  AddFieldValue(fd, "StretchMin", result.MinStretch);
  AddFieldValue(fd, "StretchMax", result.MaxStretch);
  if (this->PreparationRequested())
  {
    AddFieldValue(fd, "MetricPrepMedianChange", this->MedianChange);
    AddFieldValue(fd, "MetricPrepP95Change", this->Percentile95Change);
    AddFieldValue(fd, "MetricPrepMaxChange", this->PreparationFigures[0]);
    AddFieldValue(fd, "MetricPrepChangedFraction", this->ChangedFraction);
    AddFieldValue(fd, "MetricComplexity", this->PreparationFigures[1]);
    AddFieldValue(fd, "CellUnitScale", this->CellUnitScale);
    AddFieldValue(fd, "ImpliedSites", this->ImpliedSites);
    AddFieldValue(fd, "NumGraded", static_cast<double>(this->NumberOfGradedPoints));
    AddFieldValue(fd, "NumHMinClamped", this->PreparationFigures[2]);
    AddFieldValue(fd, "NumHMaxClamped", this->PreparationFigures[3]);
    AddFieldValue(fd, "GradationSweeps", this->PreparationFigures[4]);
    AddFieldValue(fd, "CellsAcross", this->PreparationFigures[5]);
    AddFieldValue(fd, "NumThicknessLimited", this->PreparationFigures[6]);
  }
}

void vtkAnisoTensorToMetric::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Interpretation: "
     << (this->Interpretation == TENSOR_AS_METRIC ? "TensorAsMetric" : "EigenvaluesAsStretch")
     << "\n";
  os << indent << "EigenvalueMode: " << (this->EigenvalueMode == CLAMP ? "Clamp" : "Absolute")
     << "\n";
  os << indent << "MinimumEigenvalue: " << this->MinimumEigenvalue << "\n";
  os << indent << "MaximumAnisotropy: " << this->MaximumAnisotropy << "\n";
  os << indent << "SmoothingIterations: " << this->SmoothingIterations << "\n";
  os << indent << "Dimension: "
     << (this->Dimension == DIMENSION_AUTO ? std::string("Auto") : std::to_string(this->Dimension))
     << "\n";
  os << indent << "ApplyGlobalScale: " << this->ApplyGlobalScale << "\n";
  os << indent << "ProjectOntoSurface: " << this->ProjectOntoSurface << "\n";
  os << indent << "MetricArrayName: " << (this->MetricArrayName ? this->MetricArrayName : "")
     << "\n";
  const char* sizeModes[] = { "Tensor", "Uniform", "Blend" };
  os << indent << "SizeMode: " << sizeModes[this->SizeMode] << "\n";
  os << indent << "SizeBlend: " << this->SizeBlend << "\n";
  os << indent << "NumberOfSites: " << this->NumberOfSites << "\n";
  os << indent << "HMin: " << this->HMin << "\n";
  os << indent << "HMax: " << this->HMax << "\n";
  os << indent << "MinCellsAcross: " << this->MinCellsAcross << "\n";
  os << indent << "Gradation: " << this->Gradation << "\n";
  os << indent << "GradationFactor: " << this->GradationFactor << "\n";
}
