// SPDX-License-Identifier: BSD-3-Clause
// The anisovoronoi tool's input readers, chosen by the INPUT file's extension.
#include "InputReaders.h"

#include "CommandLine.h"
#include "OffReader.h"
#include "vtkAnisoFRDReader.h"
#include "vtkAnisoMeditReader.h"

#include <vtkCellArray.h>
#include <vtkDataSetReader.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkTriangleFilter.h>
#include <vtkTrivialProducer.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtksys/SystemTools.hxx>

namespace avcli
{
namespace
{
/// An OFF surface (the kernel's reader) as a triangle vtkPolyData behind a trivial producer.
vtkSmartPointer<vtkAlgorithm> ReadOffSurface(const std::string& path)
{
  av::SimplexMesh surfaceMesh;
  try
  {
    surfaceMesh = av::ReadOff(path);
  }
  catch (const av::InputError& e)
  {
    Fail(std::string("read ") + vtksys::SystemTools::GetFilenameName(path) + ": " + e.what());
  }
  auto grid = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (std::size_t i = 0; i < surfaceMesh.NumPoints(); ++i)
    points->InsertNextPoint(surfaceMesh.Point(i));
  vtkNew<vtkCellArray> triangles;
  for (std::size_t c = 0; c < surfaceMesh.NumCells(); ++c)
  {
    const vtkIdType ids[3] = {
      surfaceMesh.Cell(c)[0], surfaceMesh.Cell(c)[1], surfaceMesh.Cell(c)[2]
    };
    triangles->InsertNextCell(3, ids);
  }
  grid->SetPoints(points);
  grid->SetPolys(triangles);
  auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
  producer->SetOutput(grid);
  return producer;
}
} // namespace

/// Reads INPUT by its extension; returns the algorithm producing it.
vtkSmartPointer<vtkAlgorithm> MakeReader(const Options& o)
{
  if (!vtksys::SystemTools::FileExists(o.Input, true))
    Fail("cannot read '" + o.Input + "': no such file");
  const std::string ext =
    vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(o.Input));
  if (ext == ".mesh" || ext == ".meshb")
  {
    auto r = vtkSmartPointer<vtkAnisoMeditReader>::New();
    r->SetFileName(o.Input.c_str());
    if (!o.Sol.empty())
      r->SetSolFileName(o.Sol.c_str());
    return r;
  }
  if (!o.Sol.empty())
    Fail("--sol is only meaningful with a Medit .mesh/.meshb INPUT", 2);
  if (ext == ".frd")
  {
    auto r = vtkSmartPointer<vtkAnisoFRDReader>::New();
    r->SetFileName(o.Input.c_str());
    r->SetStepIndex(o.Step);
    return r;
  }
  if (ext == ".vtk")
  {
    auto r = vtkSmartPointer<vtkDataSetReader>::New();
    r->SetFileName(o.Input.c_str());
    r->ReadAllTensorsOn();
    r->ReadAllScalarsOn();
    r->ReadAllVectorsOn();
    r->ReadAllFieldsOn();
    return r;
  }
  if (ext == ".vtu" || ext == ".vtp" || ext == ".vts" || ext == ".vtr" || ext == ".vti")
  {
    auto r = vtkSmartPointer<vtkXMLGenericDataObjectReader>::New();
    r->SetFileName(o.Input.c_str());
    return r;
  }
  vtkSmartPointer<vtkAlgorithm> surface;
  if (ext == ".stl")
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else if (ext == ".ply")
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else if (ext == ".off")
  {
    return ReadOffSurface(o.Input);
  }
  else if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(o.Input.c_str());
    surface = r;
  }
  else
  {
    Fail("unsupported INPUT extension '" + ext +
      "' (use .vtk .vtu .vtp .mesh .meshb .frd .stl .ply .obj .off)");
  }
  // Surfaces: polygons -> triangles.
  auto tri = vtkSmartPointer<vtkTriangleFilter>::New();
  tri->SetInputConnection(surface->GetOutputPort());
  tri->PassVertsOff();
  tri->PassLinesOff();
  return tri;
}

} // namespace avcli
