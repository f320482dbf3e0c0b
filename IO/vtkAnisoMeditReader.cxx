// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAnisoMeditReader.h"

#include "MeditBinaryIO.h"
#include "vtkAnisoDataConversion.h"
#include "vtkAnisoFilterUtilities.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>

vtkStandardNewMacro(vtkAnisoMeditReader);

vtkAnisoMeditReader::vtkAnisoMeditReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkAnisoMeditReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro("FileName is not set.");
    return 0;
  }
  const bool ok = vtkAnisoFilterUtilities::RunKernel(this,
    ("reading " + this->FileName).c_str(),
    [&]
    {
      const av::MeditMesh m = av::ReadMeditMeshFile(this->FileName);
      const av::SimplexMesh& mesh = m.Mesh;
      const vtkIdType np = static_cast<vtkIdType>(mesh.NumPoints());
      auto points = vtkSmartPointer<vtkPoints>::New();
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(np);
      for (vtkIdType i = 0; i < np; ++i)
      {
        const double* p = mesh.Point(static_cast<std::size_t>(i));
        points->SetPoint(i, p[0], p[1], mesh.AmbientDim == 3 ? p[2] : 0.0);
      }
      const int k = mesh.VerticesPerCell();
      const vtkIdType nc = static_cast<vtkIdType>(mesh.NumCells());
      auto cells = vtkSmartPointer<vtkCellArray>::New();
      cells->AllocateExact(nc, nc * k);
      vtkIdType ids[4];
      for (vtkIdType c = 0; c < nc; ++c)
      {
        const std::int32_t* cell = mesh.Cell(static_cast<std::size_t>(c));
        std::copy(cell, cell + k, ids);
        cells->InsertNextCell(k, ids);
      }
      output->SetPoints(points);
      output->SetCells(mesh.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE, cells);
      output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeIntArray("Ref", m.PointRefs));
      output->GetCellData()->AddArray(vtkAnisoDataConversion::MakeIntArray("Ref", m.CellRefs));
      // MMG's ridges and corners, as the feature lines the sampler keeps its sites on.
      if (!m.Ridges.empty() || !m.Corners.empty())
      {
        std::vector<std::int32_t> ridgeEdges;
        for (std::int32_t r : m.Ridges)
        {
          ridgeEdges.push_back(m.Edges[2 * static_cast<std::size_t>(r)]);
          ridgeEdges.push_back(m.Edges[2 * static_cast<std::size_t>(r) + 1]);
        }
        vtkAnisoDataConversion::AddFeatureFieldData(output->GetFieldData(), ridgeEdges, m.Corners);
      }

      if (!this->SolFileName.empty())
      {
        const av::MeditSol sol = av::ReadMeditSolFile(this->SolFileName);
        if (sol.NumVertices != mesh.NumPoints())
        {
          throw av::InputError("The .sol file " + this->SolFileName + " has " +
            std::to_string(sol.NumVertices) + " vertices but the mesh has " + std::to_string(np) +
            ".");
        }
        int metricField = -1, sizeField = -1;
        for (std::size_t f = 0; f < sol.FieldTypes.size(); ++f)
        {
          if (sol.FieldTypes[f] == 3 && metricField < 0)
          {
            metricField = static_cast<int>(f);
          }
          if (sol.FieldTypes[f] == 1 && sizeField < 0)
          {
            sizeField = static_cast<int>(f);
          }
        }
        const int fromField = metricField >= 0 ? metricField : sizeField;
        if (fromField >= 0)
        {
          const av::MetricField metric =
            av::MetricFromMeditSol(sol, static_cast<std::size_t>(fromField));
          output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeArray(
            "Metric", metric.Values.data(), metric.NumPoints(), 6));
          output->GetPointData()->SetActiveTensors("Metric");
        }
        for (std::size_t f = 0; f < sol.FieldTypes.size(); ++f)
        {
          const int fi = static_cast<int>(f);
          if (fi == metricField)
          {
            continue;
          }
          const std::string name =
            fi == sizeField ? std::string("Size") : "SolField" + std::to_string(f);
          const int nc = sol.FieldComponents(sol.FieldTypes[f]);
          output->GetPointData()->AddArray(vtkAnisoDataConversion::MakeArray(
            name.c_str(), sol.Fields[f].data(), sol.Fields[f].size() / nc, nc));
        }
      }
    });
  if (!ok)
  {
    output->Initialize();
    return 0;
  }
  return 1;
}

void vtkAnisoMeditReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SolFileName: " << this->SolFileName << "\n";
}
