// SPDX-License-Identifier: BSD-3-Clause
#include "MeditOutput.h"

#include "CommandLine.h"
#include "vtkAnisoMeditWriter.h"

#include <vtkDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>

namespace avcli
{

std::string SolPathFor(const std::string& meshPath)
{
  const std::size_t dot = meshPath.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : meshPath.substr(dot);
  const bool binary = ext == ".meshb" || ext == ".MESHB";
  return (dot == std::string::npos ? meshPath : meshPath.substr(0, dot)) +
    (binary ? ".solb" : ".sol");
}

void WriteMeditOutput(vtkDataObject* mesh, const std::string& meshPath)
{
  vtkDataSet* ds = vtkDataSet::SafeDownCast(mesh);
  if (!ds || ds->GetNumberOfCells() == 0)
    Fail("no mesh to write to " + meshPath);
  if (!ds->GetPointData()->GetArray("Metric"))
    Fail("the mesh has no \"Metric\" point array to write to " + SolPathFor(meshPath));
  vtkNew<vtkAnisoMeditWriter> writer;
  writer->SetInputData(ds);
  writer->SetFileName(meshPath.c_str());
  writer->SetSolFileName(SolPathFor(meshPath).c_str());
  writer->SetMetricArrayName("Metric");
  if (!writer->Write())
    Fail("cannot write " + meshPath + " / " + SolPathFor(meshPath));
}

} // namespace avcli
