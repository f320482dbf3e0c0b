#include "vtkAnisoRestrictedVoronoi.h"

#include "RestrictedVoronoi.h"
#include "vtkAnisoDataConversion.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkAnisoRestrictedVoronoi);

namespace
{
void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

/// Signed input-space measure (times k!) of cell c: only meaningful for flat 2D and tets.
double SignedMeasure(const av::SimplexMesh& mesh, std::size_t c)
{
  const std::int32_t* v = mesh.Cell(c);
  const int m = mesh.AmbientDim;
  if (mesh.SimplexDim == 3)
  {
    double e[3][3];
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d)
        e[a][d] = mesh.Point(v[a + 1])[d] - mesh.Point(v[0])[d];
    return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
      e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
      e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  }
  if (m == 2)
  {
    const double* p0 = mesh.Point(v[0]);
    const double* p1 = mesh.Point(v[1]);
    const double* p2 = mesh.Point(v[2]);
    return (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
  }
  // Surface triangle: unsigned area (times 2).
  const double* p0 = mesh.Point(v[0]);
  const double* p1 = mesh.Point(v[1]);
  const double* p2 = mesh.Point(v[2]);
  const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
  const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
  const double c3[3] = {
    a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
  };
  return std::sqrt(c3[0] * c3[0] + c3[1] * c3[1] + c3[2] * c3[2]);
}

using VertexKey = std::array<std::int32_t, 8>;

/// Symbolic identity of an RVD vertex across the elements of one site's cell: the bisector
/// sites and the global mesh vertices of the sub-simplex (intersection of its facet planes).
VertexKey MakeKey(const std::int32_t* planes, int k, const std::int32_t* cell)
{
  VertexKey key;
  key.fill(-1);
  std::array<std::int32_t, 4> bis{};
  int nb = 0;
  bool onFacet[4] = { false, false, false, false };
  for (int a = 0; a < k; ++a)
  {
    if (planes[a] >= 0)
      bis[nb++] = planes[a];
    else
      onFacet[-planes[a] - 1] = true;
  }
  std::sort(bis.begin(), bis.begin() + nb);
  std::array<std::int32_t, 4> verts{};
  int nvtx = 0;
  for (int a = 0; a <= k; ++a)
    if (!onFacet[a])
      verts[nvtx++] = cell[a];
  std::sort(verts.begin(), verts.begin() + nvtx);
  int n = 0;
  key[n++] = nb;
  for (int i = 0; i < nb; ++i)
    key[n++] = bis[i];
  for (int i = 0; i < nvtx; ++i)
    key[n++] = verts[i];
  return key;
}

/// Accumulates the output cells and their faces (points never shared between cells).
struct OutputBuilder
{
  int K = 3;
  double Shrink = 1.0;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Cells;
  vtkNew<vtkIdTypeArray> FaceStream; // polyhedra only
  vtkNew<vtkIdTypeArray> FaceLocations;
  std::vector<unsigned char> Types;
  vtkNew<vtkIntArray> SiteId, ElementId;
  vtkNew<vtkDoubleArray> Measure, EmbeddedMeasure;
  vtkNew<vtkCellArray> FacePolys; // faces (3D) or edges (2D) of every cell
  vtkNew<vtkIntArray> FaceSite, FaceKind, FaceNeighbor;

  // Scratch of the current cell: local points and faces (local ids).
  std::vector<std::array<double, 3>> P, Q;
  std::vector<vtkIdType> FaceIds; // concatenated
  std::vector<int> FaceSizes, Kinds, Neighbors;
  std::vector<vtkIdType> Loop; // 2D polygon loop (local ids)
  std::vector<vtkIdType> Ids, Remap;

  OutputBuilder()
  {
    this->Points->SetDataTypeToDouble();
    this->SiteId->SetName("SiteId");
    this->ElementId->SetName("ElementId");
    this->Measure->SetName("Measure");
    this->EmbeddedMeasure->SetName("EmbeddedMeasure");
    this->FaceSite->SetName("SiteId");
    this->FaceKind->SetName("FaceKind");
    this->FaceNeighbor->SetName("NeighborSiteId");
  }

  void Begin()
  {
    this->P.clear();
    this->FaceIds.clear();
    this->FaceSizes.clear();
    this->Kinds.clear();
    this->Neighbors.clear();
    this->Loop.clear();
  }

  void AddFace(const vtkIdType* ids, int n, av::RVDFaceKind kind, std::int32_t nbr)
  {
    this->FaceIds.insert(this->FaceIds.end(), ids, ids + n);
    this->FaceSizes.push_back(n);
    this->Kinds.push_back(static_cast<int>(kind));
    this->Neighbors.push_back(kind == av::RVDFaceKind::Bisector ? nbr : -1);
  }

  /// Drops the points no kept face uses (mesh vertices inside a merged cell, or points only on
  /// dropped element faces) and renumbers faces and loop.
  void Compact()
  {
    std::vector<vtkIdType>& remap = this->Remap;
    remap.assign(this->P.size(), -1);
    this->Q.clear();
    for (vtkIdType& id : this->FaceIds)
    {
      if (remap[id] < 0)
      {
        remap[id] = static_cast<vtkIdType>(this->Q.size());
        this->Q.push_back(this->P[id]);
      }
      id = remap[id];
    }
    for (vtkIdType& id : this->Loop)
      id = remap[id];
    this->P.swap(this->Q);
  }

  /// Emits the scratch cell: shrinks it about its vertex centroid, appends points and faces.
  void End(int site, int element, double measure, double embMeasure)
  {
    this->Compact();
    const std::size_t np = this->P.size();
    if (np == 0 || this->FaceSizes.empty())
      return;
    double c[3] = { 0, 0, 0 };
    for (const auto& p : this->P)
      for (int d = 0; d < 3; ++d)
        c[d] += p[d];
    for (double& v : c)
      v /= static_cast<double>(np);
    const vtkIdType base = this->Points->GetNumberOfPoints();
    for (const auto& p : this->P)
      this->Points->InsertNextPoint(c[0] + this->Shrink * (p[0] - c[0]),
        c[1] + this->Shrink * (p[1] - c[1]),
        c[2] + this->Shrink * (p[2] - c[2]));
    const double scale = std::pow(this->Shrink, this->K);
    if (this->K == 3)
    {
      this->Ids.resize(np);
      for (std::size_t i = 0; i < np; ++i)
        this->Ids[i] = base + static_cast<vtkIdType>(i);
      this->Cells->InsertNextCell(static_cast<vtkIdType>(np), this->Ids.data());
      this->FaceLocations->InsertNextValue(this->FaceStream->GetNumberOfTuples());
      this->FaceStream->InsertNextValue(static_cast<vtkIdType>(this->FaceSizes.size()));
      std::size_t off = 0;
      for (int n : this->FaceSizes)
      {
        this->FaceStream->InsertNextValue(n);
        for (int t = 0; t < n; ++t)
          this->FaceStream->InsertNextValue(base + this->FaceIds[off + t]);
        off += n;
      }
      this->Types.push_back(VTK_POLYHEDRON);
    }
    else
    {
      this->Ids.resize(this->Loop.size());
      for (std::size_t i = 0; i < this->Loop.size(); ++i)
        this->Ids[i] = base + this->Loop[i];
      this->Cells->InsertNextCell(static_cast<vtkIdType>(this->Ids.size()), this->Ids.data());
      this->FaceLocations->InsertNextValue(-1);
      this->Types.push_back(VTK_POLYGON);
    }
    this->SiteId->InsertNextValue(site);
    this->ElementId->InsertNextValue(element);
    this->Measure->InsertNextValue(measure * scale);
    this->EmbeddedMeasure->InsertNextValue(embMeasure * scale);
    std::size_t off = 0;
    for (std::size_t f = 0; f < this->FaceSizes.size(); ++f)
    {
      const int n = this->FaceSizes[f];
      this->Ids.resize(n);
      for (int t = 0; t < n; ++t)
        this->Ids[t] = base + this->FaceIds[off + t];
      off += n;
      this->FacePolys->InsertNextCell(n, this->Ids.data());
      this->FaceSite->InsertNextValue(site);
      this->FaceKind->InsertNextValue(this->Kinds[f]);
      this->FaceNeighbor->InsertNextValue(this->Neighbors[f]);
    }
  }
};
} // namespace

vtkAnisoRestrictedVoronoi::vtkAnisoRestrictedVoronoi()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Embedding");
}

void vtkAnisoRestrictedVoronoi::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

int vtkAnisoRestrictedVoronoi::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkAnisoRestrictedVoronoi::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

int vtkAnisoRestrictedVoronoi::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every process needs the whole mesh and all sites; only the clipping work is split.
  vtkAnisoDataConversion::RequestWholeInputs(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkAnisoRestrictedVoronoi::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkDataSet* sitesInput = vtkDataSet::GetData(inputVector[1]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* faces = vtkPolyData::GetData(outputVector, 1);
  if (!input || input->GetNumberOfPoints() == 0 || input->GetNumberOfCells() == 0 || !sitesInput ||
    sitesInput->GetNumberOfPoints() == 0)
  {
    return 1; // empty in, empty out
  }
  const auto start = std::chrono::steady_clock::now();

  av::SimplexMesh mesh;
  av::Embedding embedding;
  av::SiteSet sites;
  std::string error, note;
  if (!vtkAnisoDataConversion::ToVoronoiInputs(input, this->GetInputArrayToProcess(0, inputVector),
        sitesInput, mesh, embedding, sites, error, &note))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (!note.empty())
  {
    vtkWarningMacro(<< note);
  }
  this->UpdateProgress(0.1);

  av::RestrictedVoronoiOptions options;
  options.ComputeGeometry = true;
  options.KeepEmbeddedPoints = false;
  options.MergeBySite = this->MergeBySite;
  // Distributed run: this piece clips one contiguous block of elements.
  int piece = 0, numberOfPieces = 1;
  vtkAnisoDataConversion::RequestedPiece(request, outputVector, piece, numberOfPieces);
  const std::int64_t numberOfElements = static_cast<std::int64_t>(mesh.NumCells());
  options.ElementBegin = numberOfElements * piece / numberOfPieces;
  options.ElementEnd = numberOfElements * (piece + 1) / numberOfPieces;
  av::RestrictedVoronoiDiagram rvd;
  double kernelSeconds = 0.0;
  try
  {
    av::ValidateRestrictedVoronoiInput(mesh, embedding, sites);
    const auto kernelStart = std::chrono::steady_clock::now();
    rvd = av::ComputeRestrictedVoronoi(mesh, embedding, sites, options);
    kernelSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - kernelStart).count();
  }
  catch (const av::InputError& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("restricted Voronoi diagram failed: " << e.what());
    return 0;
  }
  if (this->GetAbortExecute())
  {
    return 1;
  }
  this->UpdateProgress(0.6);

  const int K = mesh.SimplexDim, adim = mesh.AmbientDim;
  const bool orientable = K == 3 || adim == 2;
  std::vector<unsigned char> flip(mesh.NumCells(), 0);
  double domain = 0.0;
  for (std::size_t c = 0; c < mesh.NumCells(); ++c)
  {
    const double s = SignedMeasure(mesh, c);
    flip[c] = orientable && s < 0;
    domain += std::abs(s) / (K == 3 ? 6.0 : 2.0);
  }

  OutputBuilder out;
  out.K = K;
  out.Shrink = this->ShrinkFactor;
  auto point = [&](std::int64_t v)
  {
    const double* x = rvd.Points.data() + v * adim;
    return std::array<double, 3>{ x[0], x[1], adim == 3 ? x[2] : 0.0 };
  };

  std::vector<vtkIdType> pieceIds;
  // Emits piece p on its own (MergeBySite off, or a 2D cell that is not one simple loop).
  auto emitPiece = [&](std::size_t p)
  {
    out.Begin();
    const std::int64_t v0 = rvd.PieceVertexOffsets[p], v1 = rvd.PieceVertexOffsets[p + 1];
    const bool f = flip[rvd.PieceElement[p]];
    for (std::int64_t v = v0; v < v1; ++v)
      out.P.push_back(point(v));
    if (K == 2)
    {
      for (std::int64_t v = v0; v < v1; ++v)
        out.Loop.push_back(f ? v1 - 1 - v : v - v0);
    }
    std::vector<vtkIdType>& ids = pieceIds;
    for (std::int64_t fc = rvd.PieceFaceOffsets[p]; fc < rvd.PieceFaceOffsets[p + 1]; ++fc)
    {
      ids.clear();
      for (std::int64_t i = rvd.FaceOffsets[fc]; i < rvd.FaceOffsets[fc + 1]; ++i)
        ids.push_back(rvd.FaceVertices[i] - v0);
      if (f)
        std::reverse(ids.begin(), ids.end());
      out.AddFace(ids.data(), static_cast<int>(ids.size()), rvd.FaceKind[fc], rvd.FaceNeighbor[fc]);
    }
    out.End(
      rvd.PieceSite[p], rvd.PieceElement[p], rvd.PieceMeasure[p], rvd.PieceEmbeddedMeasure[p]);
  };

  const std::size_t np = rvd.NumPieces();
  std::size_t nonEmpty = 0;
  if (!this->MergeBySite)
  {
    for (std::size_t p = 0; p < np; ++p)
      emitPiece(p);
    std::vector<unsigned char> seen(sites.NumSites(), 0);
    for (std::size_t p = 0; p < np; ++p)
      seen[rvd.PieceSite[p]] = 1;
    nonEmpty = static_cast<std::size_t>(std::count(seen.begin(), seen.end(), 1));
  }
  else
  {
    std::vector<std::pair<VertexKey, std::int64_t>> keys;
    std::vector<vtkIdType> localOf, ids, nextOf, loop;
    for (std::size_t p0 = 0; p0 < np;)
    {
      std::size_t p1 = p0;
      const std::int32_t site = rvd.PieceSite[p0];
      double measure = 0.0, embMeasure = 0.0;
      while (p1 < np && rvd.PieceSite[p1] == site)
      {
        measure += rvd.PieceMeasure[p1];
        embMeasure += rvd.PieceEmbeddedMeasure[p1];
        ++p1;
      }
      ++nonEmpty;
      // The site's vertices are contiguous: deduplicate them by their symbolic key.
      const std::int64_t vb = rvd.PieceVertexOffsets[p0], ve = rvd.PieceVertexOffsets[p1];
      keys.clear();
      for (std::size_t p = p0; p < p1; ++p)
      {
        const std::int32_t* cell = mesh.Cell(rvd.PieceElement[p]);
        for (std::int64_t v = rvd.PieceVertexOffsets[p]; v < rvd.PieceVertexOffsets[p + 1]; ++v)
          keys.emplace_back(MakeKey(rvd.VertexPlanes.data() + v * K, K, cell), v);
      }
      std::sort(keys.begin(), keys.end());
      out.Begin();
      localOf.assign(static_cast<std::size_t>(ve - vb), -1);
      for (std::size_t i = 0; i < keys.size(); ++i)
      {
        if (i == 0 || keys[i].first != keys[i - 1].first)
          out.P.push_back(point(keys[i].second));
        localOf[keys[i].second - vb] = static_cast<vtkIdType>(out.P.size() - 1);
      }
      for (std::size_t p = p0; p < p1; ++p)
      {
        const bool f = flip[rvd.PieceElement[p]];
        for (std::int64_t fc = rvd.PieceFaceOffsets[p]; fc < rvd.PieceFaceOffsets[p + 1]; ++fc)
        {
          ids.clear();
          for (std::int64_t i = rvd.FaceOffsets[fc]; i < rvd.FaceOffsets[fc + 1]; ++i)
          {
            const vtkIdType l = localOf[rvd.FaceVertices[i] - vb];
            if (ids.empty() || ids.back() != l)
              ids.push_back(l);
          }
          while (ids.size() > 1 && ids.front() == ids.back())
            ids.pop_back();
          if (ids.size() < static_cast<std::size_t>(K))
            continue; // collapsed (degenerate) face
          if (f)
            std::reverse(ids.begin(), ids.end());
          out.AddFace(
            ids.data(), static_cast<int>(ids.size()), rvd.FaceKind[fc], rvd.FaceNeighbor[fc]);
        }
      }
      bool ok = true;
      if (K == 2)
      {
        // Chain the kept edges into one loop; anything else (holes, several components,
        // inconsistent orientation) falls back to one polygon per piece.
        const std::size_t nl = out.P.size(), ne = out.FaceSizes.size();
        nextOf.assign(nl, -1);
        for (std::size_t e = 0; e < ne && ok; ++e)
        {
          const vtkIdType a = out.FaceIds[2 * e], b = out.FaceIds[2 * e + 1];
          if (nextOf[a] >= 0)
            ok = false;
          nextOf[a] = b;
        }
        loop.clear();
        if (ok && ne > 0)
        {
          vtkIdType v = out.FaceIds[0];
          do
          {
            loop.push_back(v);
            v = nextOf[v];
          } while (v >= 0 && v != out.FaceIds[0] && loop.size() <= ne);
          ok = v == out.FaceIds[0] && loop.size() == ne;
        }
        out.Loop = loop;
      }
      if (ok)
      {
        out.End(site, -1, measure, embMeasure);
      }
      else
      {
        for (std::size_t p = p0; p < p1; ++p)
          emitPiece(p);
      }
      p0 = p1;
      if ((nonEmpty & 1023) == 0 && this->GetAbortExecute())
        break;
    }
  }
  this->UpdateProgress(0.9);

  output->SetPoints(out.Points);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfTuples(static_cast<vtkIdType>(out.Types.size()));
  std::copy(out.Types.begin(), out.Types.end(), types->GetPointer(0));
  if (K == 3)
    output->SetCells(types, out.Cells, out.FaceLocations, out.FaceStream);
  else
    output->SetCells(types, out.Cells);
  output->GetCellData()->AddArray(out.SiteId);
  output->GetCellData()->SetActiveScalars("SiteId");
  output->GetCellData()->AddArray(out.Measure);
  output->GetCellData()->AddArray(out.EmbeddedMeasure);
  output->GetCellData()->AddArray(out.ElementId);

  faces->SetPoints(out.Points);
  if (K == 3)
    faces->SetPolys(out.FacePolys);
  else
    faces->SetLines(out.FacePolys);
  faces->GetCellData()->AddArray(out.FaceSite);
  faces->GetCellData()->AddArray(out.FaceKind);
  faces->GetCellData()->SetActiveScalars("FaceKind");
  faces->GetCellData()->AddArray(out.FaceNeighbor);

  double total = 0.0;
  for (double m : rvd.PieceMeasure)
    total += m;
  this->TotalMeasure = total;
  this->DomainMeasure = domain;
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (vtkDataObject* o :
    { static_cast<vtkDataObject*>(output), static_cast<vtkDataObject*>(faces) })
  {
    vtkFieldData* fd = o->GetFieldData();
    AddFieldValue(fd, "TotalMeasure", total);
    AddFieldValue(fd, "DomainMeasure", domain);
    AddFieldValue(fd, "RelativeVolumeError", domain > 0 ? std::abs(total - domain) / domain : 0.0);
    AddFieldValue(fd, "NumberOfVoronoiCells", static_cast<double>(nonEmpty));
    AddFieldValue(fd, "NumberOfEmptySites", static_cast<double>(sites.NumSites() - nonEmpty));
    AddFieldValue(fd, "VoronoiKernelSeconds", kernelSeconds);
    AddFieldValue(fd, "VoronoiSeconds", seconds);
    AddFieldValue(fd, "PieceNumber", piece);
    AddFieldValue(fd, "NumberOfPieces", numberOfPieces);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkAnisoRestrictedVoronoi::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MergeBySite: " << this->MergeBySite << "\n";
  os << indent << "ShrinkFactor: " << this->ShrinkFactor << "\n";
}
