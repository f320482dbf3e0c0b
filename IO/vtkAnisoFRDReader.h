// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoFRDReader
 * @brief Reads a CalculiX / cgx ASCII result file (.frd): mesh and nodal results.
 *
 * Output: vtkUnstructuredGrid with the frd elements as VTK cells: he8 hexahedron, pe6
 * wedge, te4 tetra, he20 quadratic hexahedron, pe15 quadratic wedge, te10 quadratic tetra,
 * tr3/tr6 (quadratic) triangle, qu4/qu8 (quadratic) quad, be2 line, be3 quadratic edge.
 * Mid-edge nodes are reordered from frd to VTK order (he20, pe15; see av::FrdToVTKNodeOrder).
 *
 * Point data: "NodeId" (the frd node number), "IsCornerNode" (1 for element corners, 0 for
 * mid-edge-only nodes) and one array per result block of the selected step, named as in
 * the file ("DISP", "STRESS", ...): symmetric tensors (STRESS, TOSTRAIN, ...) as 6-component
 * arrays in VTK order XX YY ZZ XY YZ XZ, 3-component vectors (DISP, ...) as vectors,
 * anything else with the file's components. Cell data: "ElementId", "Material", "Group".
 *
 * Steps: results are grouped by the step number of their 100C header (the mode number of a
 * frequency analysis, the increment of a static one). StepIndex (0-based, default 0) picks
 * one; with ReadAllSteps on, every step is output and arrays are named NAME_<step number>.
 * Field data "StepValue" holds the header value (time or frequency) of the selected step.
 * GetNumberOfSteps() is valid after an update.
 *
 * Errors (missing file, malformed input: the message names the line, binary frd, StepIndex
 * out of range) are reported with vtkErrorMacro and RequestData returns 0.
 * Parsing is done by av::ReadFrd (Core).
 */
#ifndef vtkAnisoFRDReader_h
#define vtkAnisoFRDReader_h

#include "AnisoVoronoiIOModule.h" // export macro
#include <vtkUnstructuredGridAlgorithm.h>

#include <string> // for the file name

class ANISOVORONOIIO_EXPORT vtkAnisoFRDReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkAnisoFRDReader* New();
  vtkTypeMacro(vtkAnisoFRDReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .frd file (required).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// 0-based index of the step (mode / increment) whose results are output. Default 0.
  vtkSetClampMacro(StepIndex, int, 0, VTK_INT_MAX);
  vtkGetMacro(StepIndex, int);
  ///@}

  ///@{
  /// Output the results of every step, named NAME_<step> (default off).
  vtkSetMacro(ReadAllSteps, bool);
  vtkGetMacro(ReadAllSteps, bool);
  vtkBooleanMacro(ReadAllSteps, bool);
  ///@}

  /// Number of steps found by the last update.
  vtkGetMacro(NumberOfSteps, int);

protected:
  vtkAnisoFRDReader();
  ~vtkAnisoFRDReader() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int StepIndex = 0;
  bool ReadAllSteps = false;
  int NumberOfSteps = 0;

private:
  vtkAnisoFRDReader(const vtkAnisoFRDReader&) = delete;
  void operator=(const vtkAnisoFRDReader&) = delete;
};

#endif
