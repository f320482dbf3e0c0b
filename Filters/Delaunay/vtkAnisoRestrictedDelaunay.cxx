#include "vtkAnisoRestrictedDelaunay.h"

#include "RestrictedDelaunay.h"
#include "RestrictedDelaunayRefinement.h"
#include "SiteImprovement.h"
#include "RestrictedVoronoi.h"
#include "vtkAnisoDataConversion.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <utility>

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

/// Output point data: the sites' arrays, recomputed for moved sites and extended to the
/// inserted ones ("CellId" / "Barycentric" are theirs, arrays the mesh also has are
/// interpolated, others 0).
void ExtendPointData(vtkDataSet* sitesInput, vtkDataSet* meshInput,
  const av::SimplexMesh& mesh, const av::SiteSet& sites, const std::vector<char>& moved,
  vtkUnstructuredGrid* output)
{
  vtkPointData* in = sitesInput->GetPointData();
  vtkPointData* meshPD = meshInput->GetPointData();
  vtkPointData* out = output->GetPointData();
  const vtkIdType n0 = sitesInput->GetNumberOfPoints();
  const vtkIdType n = static_cast<vtkIdType>(sites.NumSites());
  const int nv = mesh.SimplexDim + 1;
  vtkNew<vtkIdList> cellPoints;
  cellPoints->SetNumberOfIds(nv);
  double weights[4];
  for (int a = 0; a < in->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* src = in->GetArray(a); // null for non-numeric arrays: not carried over
    if (!src)
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n0; ++i)
    {
      dst->SetTuple(i, i, src);
    }
    const auto changed = [&](vtkIdType i) { return i >= n0 || moved[static_cast<std::size_t>(i)]; };
    const std::string name = src->GetName() ? src->GetName() : "";
    vtkDataArray* meshArray = name.empty() ? nullptr : meshPD->GetArray(name.c_str());
    if (meshArray && meshArray->GetNumberOfComponents() != src->GetNumberOfComponents())
    {
      meshArray = nullptr;
    }
    const int nc = src->GetNumberOfComponents();
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (!changed(i))
      {
        continue;
      }
      const std::int32_t cell = sites.CellIds[i];
      if (name == "CellId" && nc == 1)
      {
        dst->SetComponent(i, 0, cell);
      }
      else if (name == "Barycentric" && nc == 4)
      {
        for (int c = 0; c < 4; ++c)
          dst->SetComponent(i, c, sites.Bary[4 * i + c]);
      }
      else if (meshArray)
      {
        for (int v = 0; v < nv; ++v)
        {
          cellPoints->SetId(v, mesh.Cell(cell)[v]);
          weights[v] = sites.Bary[4 * i + v];
        }
        dst->InterpolateTuple(i, cellPoints, meshArray, weights);
      }
      else
      {
        for (int c = 0; c < nc; ++c)
          dst->SetComponent(i, c, 0.0);
      }
    }
    out->AddArray(dst);
    if (in->GetTensors() == src)
    {
      out->SetActiveTensors(dst->GetName());
    }
    if (in->GetScalars() == src)
    {
      out->SetActiveScalars(dst->GetName());
    }
  }
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

  av::DelaunayRepairResult repaired;
  std::vector<char> moved(sites.NumSites(), 0); // by the improvement rounds
  std::size_t numSlivers = 0;
  std::size_t numOdtMoved = 0; // by the first round's ODT steps
  auto repairStart = std::chrono::steady_clock::now();
  double repairSeconds = 0.0;
  try
  {
    av::ValidateRestrictedVoronoiInput(mesh, embedding, sites);
    av::DelaunayRepairOptions options; // its Voronoi options: no geometry, records only
    options.MaxRounds = this->RepairInverted ? this->MaxRepairRounds : 0;
    options.RepairNonManifold = this->RepairNonManifold;
    // Computed once for every diagram and site move below.
    const std::vector<std::int32_t> adjacency = av::ComputeElementAdjacency(mesh);
    options.Voronoi.ElementAdjacency = &adjacency;
    av::RestrictedVoronoiDiagram rvd =
      av::ComputeRestrictedVoronoi(mesh, embedding, sites, options.Voronoi);
    if (this->GetAbortExecute())
    {
      return 1;
    }
    this->UpdateProgress(0.5);
    av::RestrictedDelaunayMesh rdt = av::ComputeRestrictedDelaunay(mesh, embedding, sites, rvd);
    if (this->GetAbortExecute())
    {
      return 1;
    }
    this->UpdateProgress(0.6);
    av::SiteImprovementOptions improve;
    improve.OdtIterations = this->OdtIterations;
    improve.ElementAdjacency = &adjacency;
    // The sampler's corner and feature-line sites ("FeatureKind" != 0) are not pushed off
    // their features.
    std::vector<std::uint8_t> fixedSites;
    if (vtkDataArray* kind = sitesInput->GetPointData()->GetArray("FeatureKind"))
    {
      if (kind->GetNumberOfComponents() != 1 ||
        kind->GetNumberOfTuples() != static_cast<vtkIdType>(sites.NumSites()))
      {
        vtkErrorMacro("sites: the FeatureKind array must have one component per site");
        return 0;
      }
      fixedSites.resize(sites.NumSites());
      for (std::size_t i = 0; i < fixedSites.size(); ++i)
        fixedSites[i] = kind->GetTuple1(static_cast<vtkIdType>(i)) != 0.0 ? 1 : 0;
      improve.Sliver.FixedSites = &fixedSites;
    }
    for (int round = 0; round < this->ImprovementRounds; ++round)
    {
      av::SiteImprovementResult sp = av::ImproveSites(mesh, embedding, sites, rvd, rdt, improve);
      if (sp.NumMovedSites == 0)
      {
        break;
      }
      for (std::size_t i = 0; i < sites.NumSites(); ++i)
      {
        moved[i] = moved[i] || sp.Sites.CellIds[i] != sites.CellIds[i] ||
          !std::equal(sp.Sites.Bary.begin() + 4 * i, sp.Sites.Bary.begin() + 4 * i + 4,
            sites.Bary.begin() + 4 * i);
      }
      numSlivers += round == 0 ? sp.NumSlivers : 0;
      numOdtMoved += round == 0 ? sp.NumOdtMoved : 0;
      sites = std::move(sp.Sites);
      rvd = av::ComputeRestrictedVoronoi(mesh, embedding, sites, options.Voronoi);
      rdt = av::ComputeRestrictedDelaunay(mesh, embedding, sites, rvd);
      if (this->GetAbortExecute())
      {
        return 1;
      }
    }
    this->UpdateProgress(0.8);
    repairStart = std::chrono::steady_clock::now();
    repaired = av::RepairRestrictedDelaunay(
      mesh, embedding, sites, std::move(rvd), std::move(rdt), options);
    repairSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - repairStart).count();
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

  const av::RestrictedDelaunayMesh& rdt = repaired.Delaunay;
  const std::size_t ns = repaired.Sites.NumSites();
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
  // Point ids are site ids: the sites' point data carries over unchanged, extended for the
  // inserted sites.
  const std::size_t numMoved = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  if (repaired.NumInserted == 0 && numMoved == 0)
  {
    output->GetPointData()->ShallowCopy(sitesInput->GetPointData());
  }
  else
  {
    ExtendPointData(sitesInput, input, mesh, repaired.Sites, moved, output);
  }
  vtkNew<vtkUnsignedCharArray> insertedFlag;
  insertedFlag->SetName("InsertedSite");
  insertedFlag->SetNumberOfTuples(static_cast<vtkIdType>(ns));
  for (std::size_t i = 0; i < ns; ++i)
  {
    insertedFlag->SetValue(static_cast<vtkIdType>(i), i >= repaired.NumInputSites ? 1 : 0);
  }
  output->GetPointData()->AddArray(insertedFlag);
  vtkNew<vtkUnsignedCharArray> inverted;
  inverted->SetName("Inverted");
  inverted->SetNumberOfTuples(static_cast<vtkIdType>(nc));
  std::copy(rdt.Inverted.begin(), rdt.Inverted.end(), inverted->GetPointer(0));
  output->GetCellData()->AddArray(inverted);

  this->NumberOfInverted = static_cast<vtkIdType>(rdt.NumInverted);
  this->NumberOfNonManifoldFaces = static_cast<vtkIdType>(rdt.NumNonManifoldFaces);
  this->NumberOfInsertedSites = static_cast<vtkIdType>(repaired.NumInserted);
  this->NumberOfRepairRounds = repaired.Rounds;
  vtkFieldData* fd = output->GetFieldData();
  AddFieldValue(fd, "NumInverted", static_cast<double>(rdt.NumInverted));
  AddFieldValue(fd, "NumNonManifoldFaces", static_cast<double>(rdt.NumNonManifoldFaces));
  AddFieldValue(fd, "NumOpenInteriorFaces", static_cast<double>(rdt.NumOpenInteriorFaces));
  AddFieldValue(fd, "NumUnusedSites", static_cast<double>(rdt.NumUnusedSites));
  AddFieldValue(fd, "NumInsertedSites", static_cast<double>(repaired.NumInserted));
  AddFieldValue(fd, "RepairRounds", static_cast<double>(repaired.Rounds));
  AddFieldValue(fd, "RepairStalled", repaired.Stalled ? 1.0 : 0.0);
  AddFieldValue(fd, "NumInvertedBeforeRepair", static_cast<double>(repaired.InitialInverted));
  AddFieldValue(fd, "NumNonManifoldFacesBeforeRepair",
    static_cast<double>(repaired.InitialNonManifoldFaces));
  AddFieldValue(fd, "RepairSeconds", repairSeconds);
  AddFieldValue(fd, "NumSliversPerturbed", static_cast<double>(numSlivers));
  AddFieldValue(fd, "NumMovedSites", static_cast<double>(numMoved));
  AddFieldValue(fd, "NumOdtMovedSites", static_cast<double>(numOdtMoved));
  AddFieldValue(fd,
    "DelaunaySeconds",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (rdt.NumInverted > 0 || rdt.NumNonManifoldFaces > 0)
  {
    vtkWarningMacro("the dual mesh has " << rdt.NumInverted << " inverted element(s) and "
                                         << rdt.NumNonManifoldFaces << " non-manifold face(s) "
                                         << (!this->RepairInverted
                                                ? "(RepairInverted is off)"
                                                : repaired.Stalled
                                                ? "left: the repair stopped because insertions "
                                                  "made more elements inverted than they "
                                                  "removed (the embedding is too poor here: "
                                                  "more embedding iterations or a finer input "
                                                  "mesh help); the best state is kept"
                                                : "left after the repair (more repair rounds, "
                                                  "more sites or a better embedding reduce them)"));
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoRestrictedDelaunay::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepairInverted: " << (this->RepairInverted ? "On" : "Off") << "\n";
  os << indent << "RepairNonManifold: " << (this->RepairNonManifold ? "On" : "Off") << "\n";
  os << indent << "MaxRepairRounds: " << this->MaxRepairRounds << "\n";
  os << indent << "ImprovementRounds: " << this->ImprovementRounds << "\n";
  os << indent << "OdtIterations: " << this->OdtIterations << "\n";
  os << indent << "NumberOfInsertedSites (last run): " << this->NumberOfInsertedSites << "\n";
  os << indent << "NumberOfRepairRounds (last run): " << this->NumberOfRepairRounds << "\n";
  os << indent << "NumberOfInverted (last run): " << this->NumberOfInverted << "\n";
  os << indent << "NumberOfNonManifoldFaces (last run): " << this->NumberOfNonManifoldFaces << "\n";
}
