// SPDX-License-Identifier: BSD-3-Clause
#include "MeditOutput.h"

#include "CommandLine.h"
#include "AtomicOutput.h"
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

void WriteMeditOutput(const AtomicOutput& output, vtkDataObject* mesh, const std::string& meshPath)
{
  vtkDataSet* ds = vtkDataSet::SafeDownCast(mesh);
  if (!ds || ds->GetNumberOfCells() == 0)
    Fail("no mesh to write to " + meshPath);
  if (!ds->GetPointData()->GetArray("Metric"))
    Fail("the mesh has no \"Metric\" point array to write to " + SolPathFor(meshPath));
  const std::string solPath = SolPathFor(meshPath);
  // The writer makes both files at once: the .sol is renamed first, then the mesh.
  output.Write(meshPath, [&](const std::string& meshTemporary) {
    output.Write(solPath, [&](const std::string& solTemporary) {
      vtkNew<vtkAnisoMeditWriter> writer;
      writer->SetInputData(ds);
      writer->SetFileName(meshTemporary.c_str());
      writer->SetSolFileName(solTemporary.c_str());
      writer->SetMetricArrayName("Metric");
      return writer->Write() != 0;
    });
    return true;
  });
}

} // namespace avcli
