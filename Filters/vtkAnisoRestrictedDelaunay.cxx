#include "vtkAnisoRestrictedDelaunay.h"

#include "RestrictedDelaunay.h"
#include "RestrictedVoronoi.h"
#include "vtkAnisoDataConversion.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <chrono>

vtkStandardNewMacro(vtkAnisoRestrictedDelaunay);

namespace
{
void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
}

vtkAnisoRestrictedDelaunay::vtkAnisoRestrictedDelaunay()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Embedding");
}

void vtkAnisoRestrictedDelaunay::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

int vtkAnisoRestrictedDelaunay::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoRestrictedDelaunay::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoRestrictedDelaunay::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* sitesInput = vtkDataSet::GetData(inputVector[1]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  if (vtkAnisoDataConversion::IsSecondaryPiece(request, outputVector))
  {
    return 1; // whole result on piece 0 only
  }
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0 || !sitesInput ||
    sitesInput->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }
  const auto start = std::chrono::steady_clock::now();

  av::SimplexMesh mesh;
  av::Embedding embedding;
  av::SiteSet sites;
  std::string error;
  if (!vtkAnisoDataConversion::ToVoronoiInputs(input, this->GetInputArrayToProcess(0, inputVector),
        sitesInput, mesh, embedding, sites, error))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  this->UpdateProgress(0.1);

  av::RestrictedDelaunayMesh rdt;
  try
  {
    av::ValidateRestrictedVoronoiInput(mesh, embedding, sites);
    av::RestrictedVoronoiOptions options;
    options.ComputeGeometry = false; // the dual needs only the Voronoi vertex records
    const av::RestrictedVoronoiDiagram rvd =
      av::ComputeRestrictedVoronoi(mesh, embedding, sites, options);
    if (this->GetAbortExecute())
    {
      return 1;
    }
    this->UpdateProgress(0.7);
    rdt = av::ComputeRestrictedDelaunay(mesh, embedding, sites, rvd);
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("restricted Delaunay mesh failed: " << e.what());
    return 0;
  }

  const std::size_t ns = sites.NumSites();
  const int adim = rdt.AmbientDim, nv = rdt.SimplexDim + 1;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(ns));
  for (std::size_t i = 0; i < ns; ++i)
  {
    const double* x = rdt.Points.data() + i * adim;
    points->SetPoint(static_cast<vtkIdType>(i), x[0], x[1], adim == 3 ? x[2] : 0.0);
  }
  output->SetPoints(points);
  const std::size_t nc = rdt.NumCells();
  output->AllocateExact(static_cast<vtkIdType>(nc), nv);
  vtkIdType ids[4];
  const int type = rdt.SimplexDim == 3 ? VTK_TETRA : VTK_TRIANGLE;
  for (std::size_t c = 0; c < nc; ++c)
  {
    for (int a = 0; a < nv; ++a)
      ids[a] = rdt.Cells[c * nv + a];
    output->InsertNextCell(type, nv, ids);
  }
  // Point ids are site ids: the sites' point data carries over unchanged.
  output->GetPointData()->ShallowCopy(sitesInput->GetPointData());
  vtkNew<vtkUnsignedCharArray> inverted;
  inverted->SetName("Inverted");
  inverted->SetNumberOfTuples(static_cast<vtkIdType>(nc));
  std::copy(rdt.Inverted.begin(), rdt.Inverted.end(), inverted->GetPointer(0));
  output->GetCellData()->AddArray(inverted);

  this->NumberOfInverted = static_cast<vtkIdType>(rdt.NumInverted);
  this->NumberOfNonManifoldFaces = static_cast<vtkIdType>(rdt.NumNonManifoldFaces);
  vtkFieldData* fd = output->GetFieldData();
  AddFieldValue(fd, "NumInverted", static_cast<double>(rdt.NumInverted));
  AddFieldValue(fd, "NumNonManifoldFaces", static_cast<double>(rdt.NumNonManifoldFaces));
  AddFieldValue(fd, "NumOpenInteriorFaces", static_cast<double>(rdt.NumOpenInteriorFaces));
  AddFieldValue(fd, "NumUnusedSites", static_cast<double>(rdt.NumUnusedSites));
  AddFieldValue(fd,
    "DelaunaySeconds",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (rdt.NumInverted > 0 || rdt.NumNonManifoldFaces > 0)
  {
    vtkWarningMacro("the dual mesh has " << rdt.NumInverted << " inverted element(s) and "
                                         << rdt.NumNonManifoldFaces
                                         << " non-manifold face(s) (not repaired; more sites or a "
                                            "better embedding reduce them)");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoRestrictedDelaunay::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfInverted (last run): " << this->NumberOfInverted << "\n";
  os << indent << "NumberOfNonManifoldFaces (last run): " << this->NumberOfNonManifoldFaces << "\n";
}
