#include "vtkAnisoTensorToMetric.h"

#include "TensorToMetric.h"

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

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkAnisoTensorToMetric);

namespace
{
void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

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

  // The tensor array: the chosen one, else active point tensors, else active cell tensors.
  int association = -1;
  vtkDataArray* tensors = this->GetInputArrayToProcess(0, inputVector, association);
  vtkInformation* arrayInfo = this->GetInputArrayInformation(0);
  if (!tensors && arrayInfo && arrayInfo->Has(vtkDataObject::FIELD_NAME()) &&
    arrayInfo->Get(vtkDataObject::FIELD_NAME()) && *arrayInfo->Get(vtkDataObject::FIELD_NAME()))
  {
    vtkErrorMacro(
      "the input has no array named '" << arrayInfo->Get(vtkDataObject::FIELD_NAME()) << "'");
    return 0;
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
    vtkErrorMacro("no tensor array was found: choose one with SetInputArrayToProcess (ParaView: "
                  "the 'Tensors' property) or make one the active point/cell tensors");
    return 0;
  }
  const std::string name = tensors->GetName() ? tensors->GetName() : "(unnamed)";
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
    association != vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    vtkErrorMacro("tensor array '" << name << "' must be a point or a cell array");
    return 0;
  }
  const int nc = tensors->GetNumberOfComponents();
  if (nc != 6 && nc != 9)
  {
    vtkErrorMacro("tensor array '" << name << "' has " << nc
                                   << " components; expected 6 (symmetric, XX YY ZZ XY YZ XZ) "
                                      "or 9 (3x3, row-major)");
    return 0;
  }
  const bool cellTensors = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const vtkIdType numCells = input->GetNumberOfCells();
  if (cellTensors && numCells == 0)
  {
    return 1;
  }

  // Point tensors (cell tensors averaged to the points); `used` maps kernel tuples to points.
  std::vector<double> values;
  std::vector<vtkIdType> used; // empty = every point, in order
  std::vector<std::int32_t> pointToTuple;
  vtkIdType numTuples = numPoints;
  if (!cellTensors)
  {
    values.resize(static_cast<std::size_t>(numPoints) * nc);
    for (vtkIdType i = 0; i < numPoints; ++i)
      tensors->GetTuple(i, values.data() + static_cast<std::size_t>(i) * nc);
  }
  else
  {
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
          vtkErrorMacro("tensor array '" << name << "' has a NaN or infinite value at cell " << c);
          return 0;
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
    pointToTuple.assign(static_cast<std::size_t>(numPoints), -1);
    for (vtkIdType p = 0; p < numPoints; ++p)
    {
      if (count[p] == 0)
        continue;
      pointToTuple[p] = static_cast<std::int32_t>(used.size());
      used.push_back(p);
      const double* s = sum.data() + static_cast<std::size_t>(p) * nc;
      for (int j = 0; j < nc; ++j)
        values.push_back(s[j] / count[p]);
    }
    numTuples = static_cast<vtkIdType>(used.size());
  }
  this->UpdateProgress(0.2);

  av::TensorToMetricOptions options;
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
    vtkErrorMacro("Dimension must be 0 (auto), 2 or 3, not " << this->Dimension);
    return 0;
  }
  this->UsedDimension = options.Dimension;

  std::vector<std::int32_t> edges;
  if (this->SmoothingIterations > 0)
  {
    edges = ExtractEdges(input);
    if (!pointToTuple.empty())
    {
      for (auto& e : edges)
        e = pointToTuple[e]; // edges come from cells, so every end point has a tuple
    }
    if (edges.empty())
    {
      vtkWarningMacro("the input has no cell edges: smoothing skipped");
      options.SmoothingIterations = 0;
    }
  }
  this->UpdateProgress(0.3);

  av::TensorToMetricResult result;
  try
  {
    result =
      av::TensorToMetric(values.data(), static_cast<std::size_t>(numTuples), nc, options, edges);
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro("tensor array '" << name << "': " << e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("tensor to metric conversion failed: " << e.what());
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
      metric->SetTypedTuple(p, options.Dimension == 2 ? identity2 : identity3);
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
  AddFieldValue(fd, "MetricScale", result.GlobalScale);
  AddFieldValue(fd, "MaxAsymmetry", result.MaxAsymmetry);
  AddFieldValue(fd, "NumNegative", static_cast<double>(result.NumNegative));
  AddFieldValue(fd, "NumClamped", static_cast<double>(result.NumClamped));
  AddFieldValue(fd, "NumCapped", static_cast<double>(result.NumCapped));
  AddFieldValue(fd, "StretchMin", result.MinStretch);
  AddFieldValue(fd, "StretchMax", result.MaxStretch);
  this->UpdateProgress(1.0);
  return 1;
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
  os << indent << "MetricArrayName: " << (this->MetricArrayName ? this->MetricArrayName : "")
     << "\n";
}
