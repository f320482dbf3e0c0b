// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoMeditWriter
 * @brief Writes a tetrahedral or triangle mesh as a Medit ASCII .mesh, and optionally a
 * 6-component tensor point array as a Medit .sol (SolAtVertices, type 3).
 *
 * Input: any vtkDataSet. If it has VTK_TETRA cells they are written as Tetrahedra and its
 * VTK_TRIANGLE cells as (boundary) Triangles; otherwise its triangles are written. Other
 * cell types are skipped with a warning. All points are written, in order.
 *
 * Dimension: 0 (default) = automatic: 2 for a triangle mesh whose z coordinates are all 0,
 * else 3; 2 or 3 forces it (2 needs a triangle mesh and drops z).
 * References come from the point and cell data arrays named RefArrayName (default "Ref",
 * written as 0 when absent).
 *
 * With SolFileName set, the point array MetricArrayName (default "Metric"; 6 components in
 * VTK order XX YY ZZ XY YZ XZ, or 9 components of a full tensor) is written in Medit order
 * m11 m21 m22 m31 m32 m33 (m11 m21 m22 in 2D). Doubles are written in their shortest exact
 * form, so reading the files back gives the same values bit for bit.
 *
 * Errors are reported with vtkErrorMacro and an error code; nothing crashes. Formatting is
 * done by av::FormatMeditMesh / av::FormatMeditSol (Core).
 */
#ifndef vtkAnisoMeditWriter_h
#define vtkAnisoMeditWriter_h

#include "AnisoVoronoiIOModule.h" // export macro
#include <vtkWriter.h>

#include <string> // for the file and array names

class vtkDataSet;

class ANISOVORONOIIO_EXPORT vtkAnisoMeditWriter : public vtkWriter
{
public:
  static vtkAnisoMeditWriter* New();
  vtkTypeMacro(vtkAnisoMeditWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .mesh file to write (required).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The .sol file to write the metric to (empty = none, the default).
  vtkSetStdStringFromCharMacro(SolFileName);
  vtkGetCharFromStdStringMacro(SolFileName);
  ///@}

  ///@{
  /// Point array written to the .sol (default "Metric").
  vtkSetStdStringFromCharMacro(MetricArrayName);
  vtkGetCharFromStdStringMacro(MetricArrayName);
  ///@}

  ///@{
  /// Point/cell arrays holding Medit references (default "Ref").
  vtkSetStdStringFromCharMacro(RefArrayName);
  vtkGetCharFromStdStringMacro(RefArrayName);
  ///@}

  ///@{
  /// Medit Dimension: 0 automatic (default), 2 or 3.
  vtkSetClampMacro(Dimension, int, 0, 3);
  vtkGetMacro(Dimension, int);
  ///@}

protected:
  vtkAnisoMeditWriter();
  ~vtkAnisoMeditWriter() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string SolFileName;
  std::string MetricArrayName = "Metric";
  std::string RefArrayName = "Ref";
  int Dimension = 0;

private:
  vtkAnisoMeditWriter(const vtkAnisoMeditWriter&) = delete;
  void operator=(const vtkAnisoMeditWriter&) = delete;
};

#endif
