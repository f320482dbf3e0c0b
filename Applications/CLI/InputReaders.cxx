// SPDX-License-Identifier: BSD-3-Clause
// The anisovoronoi tool's input readers, chosen by the INPUT file's extension.
#include "InputReaders.h"

#include "CommandLine.h"
#include "vtkAnisoFRDReader.h"
#include "vtkAnisoMeditReader.h"
#include "vtkAnisoOFFReader.h"

#include <vtkDataSetReader.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkSTLReader.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLGenericDataObjectReader.h>
#include <vtksys/SystemTools.hxx>

namespace avcli
{
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
    auto r = vtkSmartPointer<vtkAnisoOFFReader>::New();
    r->SetFileName(o.Input.c_str());
    return r; // triangles already
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
