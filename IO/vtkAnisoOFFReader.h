// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkAnisoOFFReader
 * @brief Reads an ASCII Object File Format surface (.off) as triangles.
 *
 * Output: vtkPolyData with double-precision points and one triangle per OFF triangle (polygons
 * are fanned into triangles, per-face colors are ignored). The parsing is av::ReadOff
 * (IO/Kernel/OffReader.h): '#' comments, the header on the counts' line or its own.
 *
 * Errors (no file name, missing file, truncated file, bad token, NaN, index out of range,
 * face with fewer than 3 vertices: the message names the line) are reported with
 * vtkErrorMacro and RequestData returns 0; the output is then empty.
 */
#ifndef vtkAnisoOFFReader_h
#define vtkAnisoOFFReader_h

#include "AnisoVoronoiIOModule.h" // export macro
#include <vtkPolyDataAlgorithm.h>

#include <string> // for the file name

class ANISOVORONOIIO_EXPORT vtkAnisoOFFReader : public vtkPolyDataAlgorithm
{
public:
  static vtkAnisoOFFReader* New();
  vtkTypeMacro(vtkAnisoOFFReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .off file (required).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

protected:
  vtkAnisoOFFReader();
  ~vtkAnisoOFFReader() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkAnisoOFFReader(const vtkAnisoOFFReader&) = delete;
  void operator=(const vtkAnisoOFFReader&) = delete;
};

#endif
