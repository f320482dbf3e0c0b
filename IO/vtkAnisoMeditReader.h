// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoMeditReader
 * @brief Reads a Medit ASCII mesh (.mesh) and optionally a vertex solution (.sol).
 *
 * Output: vtkUnstructuredGrid of VTK_TETRA cells if the file has Tetrahedra, else
 * VTK_TRIANGLE cells (a `Dimension 2` mesh gets z = 0). Boundary triangles next to
 * tetrahedra, edges, quads, hexahedra, prisms and other keywords are not output.
 * Cell data "Ref" and point data "Ref" hold the Medit references (int).
 *
 * With SolFileName set, the .sol (SolAtVertices, one value set per mesh vertex) adds:
 * - "Metric" (6 components, VTK order XX YY ZZ XY YZ XZ): the first tensor field
 *   (converted from Medit's m11 m21 m22 m31 m32 m33), or if there is none the first
 *   scalar field read as a size h (MMG convention) and turned into M = I / h^2;
 * - "Size" (1 component): the first scalar field, as stored;
 * - "SolField<i>": every other field, as stored (vectors with Dimension components).
 *
 * Errors (missing file, malformed input: the message names the line) are reported with
 * vtkErrorMacro and RequestData returns 0. Parsing is done by av::ParseMeditMesh (Core).
 */
#ifndef vtkAnisoMeditReader_h
#define vtkAnisoMeditReader_h

#include "AnisoVoronoiIOModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

#include <string> // for the file names

class ANISOVORONOIIO_EXPORT vtkAnisoMeditReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoMeditReader* New();
  vtkTypeMacro(vtkAnisoMeditReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .mesh file (required).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Optional .sol file with one value set per vertex (empty = none, the default).
  vtkSetStdStringFromCharMacro(SolFileName);
  vtkGetCharFromStdStringMacro(SolFileName);
  ///@}

protected:
  vtkAnisoMeditReader();
  ~vtkAnisoMeditReader() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string SolFileName;

private:
  vtkAnisoMeditReader(const vtkAnisoMeditReader&) = delete;
  void operator=(const vtkAnisoMeditReader&) = delete;
};

#endif
