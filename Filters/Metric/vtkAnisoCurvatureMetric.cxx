// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoCurvatureMetric.h"

#include "SurfaceCurvatureMetric.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellType.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAnisoCurvatureMetric);

namespace
{
/// A point array scattered from the kernel's compacted vertices (`used`; empty = identity);
/// points used by no triangle get zeros.
vtkSmartPointer<vtkDoubleArray> Scatter(const char* name,
  const std::vector<double>& values,
  int comps,
  vtkIdType numPoints,
  const std::vector<vtkIdType>& used)
{
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(comps);
  a->SetNumberOfTuples(numPoints);
  if (used.empty())
  {
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    return a;
  }
  a->FillValue(0.0);
  for (std::size_t k = 0; k < used.size(); ++k)
    std::copy(
      values.begin() + k * comps, values.begin() + (k + 1) * comps, a->GetPointer(used[k] * comps));
  return a;
}
/// The point ids of the input's triangles (vertex and line cells are skipped); false with
/// `error` when another cell type is present or there is no triangle.
bool ExtractTriangles(vtkDataSet* input, std::vector<vtkIdType>& triangles, std::string& error)
{
  vtkNew<vtkIdList> ids;
  const vtkIdType numCells = input->GetNumberOfCells();
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    const int type = input->GetCellType(c);
    if (type == VTK_VERTEX || type == VTK_POLY_VERTEX || type == VTK_LINE ||
      type == VTK_POLY_LINE || type == VTK_EMPTY_CELL)
    {
      continue;
    }
    input->GetCellPoints(c, ids);
    if (type != VTK_TRIANGLE)
    {
      if (type == VTK_POLYGON || type == VTK_QUAD || type == VTK_TRIANGLE_STRIP ||
        type == VTK_PIXEL)
      {
        error = "cell " + std::to_string(c) + " is not a triangle (" +
          std::to_string(ids->GetNumberOfIds()) +
          " points): triangulate the surface first with vtkTriangleFilter (ParaView: "
          "Triangulate)";
      }
      else
      {
        error = "cell " + std::to_string(c) +
          " is not a surface triangle: the curvature metric needs a triangle surface (extract "
          "it with vtkDataSetSurfaceFilter and vtkTriangleFilter)";
      }
      return false;
    }
    for (int k = 0; k < 3; ++k)
      triangles.push_back(ids->GetId(k));
  }
  if (triangles.empty())
  {
    error = "the input has no triangle";
    return false;
  }
  return true;
}

/// The triangle mesh of the points that triangles use (the kernel rejects unused points);
/// `used` maps its vertices to input points, left empty when every point is used.
av::SimplexMesh CompactTriangleMesh(vtkDataSet* input,
  const std::vector<vtkIdType>& triangles,
  std::vector<vtkIdType>& used)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  std::vector<std::int32_t> pointToVertex(static_cast<std::size_t>(numPoints), -1);
  av::SimplexMesh mesh;
  mesh.AmbientDim = 3;
  mesh.SimplexDim = 2;
  for (vtkIdType p : triangles)
  {
    if (pointToVertex[p] < 0)
    {
      pointToVertex[p] = 0; // mark
    }
  }
  for (vtkIdType p = 0; p < numPoints; ++p)
  {
    if (pointToVertex[p] == 0)
    {
      pointToVertex[p] = static_cast<std::int32_t>(used.size());
      used.push_back(p);
    }
  }
  mesh.Points.resize(3 * used.size());
  for (std::size_t k = 0; k < used.size(); ++k)
    input->GetPoint(used[k], mesh.Points.data() + 3 * k);
  mesh.Cells.reserve(triangles.size());
  for (vtkIdType p : triangles)
    mesh.Cells.push_back(pointToVertex[p]);
  if (used.size() == static_cast<std::size_t>(numPoints))
  {
    used.clear(); // identity map
  }
  return mesh;
}
}

vtkAnisoCurvatureMetric::vtkAnisoCurvatureMetric()
{
  this->SetMetricArrayName("Metric");
}

vtkAnisoCurvatureMetric::~vtkAnisoCurvatureMetric()
{
  this->SetMetricArrayName(nullptr);
}

int vtkAnisoCurvatureMetric::RequestData(vtkInformation*,
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
  const vtkIdType numCells = input->GetNumberOfCells();
  if (numPoints == 0 || numCells == 0)
  {
    return 1; // empty in, empty out
  }
  if (numPoints > std::numeric_limits<std::int32_t>::max())
  {
    vtkErrorMacro("too many points for 32-bit ids");
    return 0;
  }

  std::string error;
  std::vector<vtkIdType> triangles;
  if (!ExtractTriangles(input, triangles, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  std::vector<vtkIdType> used;
  const av::SimplexMesh mesh = CompactTriangleMesh(input, triangles, used);
  const bool compacted = !used.empty();
  if (compacted)
  {
    vtkWarningMacro(<< (numPoints - static_cast<vtkIdType>(used.size()))
                    << " point(s) are used by no triangle: they get a zero metric");
  }
  this->UpdateProgress(0.2);

  av::SurfaceCurvatureMetricOptions options;
  options.CurvatureThreshold = this->CurvatureThreshold;
  options.SmoothingIterations = this->SmoothingIterations;
  options.MaxStretch = this->MaxStretch;
  options.CreaseAngle = this->CreaseAngle;
  av::SurfaceCurvatureMetricResult result;
  if (!vtkAnisoFilterUtilities::RunKernel(this,
        "curvature metric",
        [&]
        {
          try
          {
            result = av::SurfaceCurvatureMetric(mesh, options);
          }
          catch (const av::InputError& e)
          {
            throw av::InputError(std::string(e.what()) +
              (compacted ? " (point/triangle ids count only the triangles' points)" : ""));
          }
        }))
  {
    return 0;
  }
  this->UpdateProgress(0.9);

  vtkPointData* pd = output->GetPointData();
  const char* metricName = this->MetricArrayName ? this->MetricArrayName : "Metric";
  pd->AddArray(Scatter(metricName, result.Metric.Values, 6, numPoints, used));
  pd->AddArray(Scatter("Stretch", result.StretchRatio, 1, numPoints, used));
  pd->AddArray(Scatter("KMin", result.MinCurvature, 1, numPoints, used));
  pd->AddArray(Scatter("KMax", result.MaxCurvature, 1, numPoints, used));
  pd->AddArray(Scatter("VMin", result.MinDirection, 3, numPoints, used));
  pd->AddArray(Scatter("VMax", result.MaxDirection, 3, numPoints, used));
  pd->SetActiveTensors(metricName);
  vtkAnisoFilterUtilities::AddFieldValue(
    output->GetFieldData(), "CurvatureFloor", result.CurvatureFloor);
  vtkAnisoFilterUtilities::AddFieldValue(
    output->GetFieldData(), "CreaseEdges", static_cast<double>(result.NumCreaseEdges));
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoCurvatureMetric::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CurvatureThreshold: " << this->CurvatureThreshold << "\n";
  os << indent << "SmoothingIterations: " << this->SmoothingIterations << "\n";
  os << indent << "MaxStretch: " << this->MaxStretch << "\n";
  os << indent << "CreaseAngle: " << this->CreaseAngle << "\n";
  os << indent << "MetricArrayName: " << (this->MetricArrayName ? this->MetricArrayName : "")
     << "\n";
}
