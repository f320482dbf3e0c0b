// SPDX-License-Identifier: BSD-3-Clause
// InputReaders: the reader of the anisovoronoi tool's INPUT (VTK legacy / XML, Medit, CalculiX
// .frd, STL / PLY / OBJ / OFF surfaces as triangles).
#ifndef avcli_InputReaders_h
#define avcli_InputReaders_h

#include <vtkAlgorithm.h>
#include <vtkSmartPointer.h>

namespace avcli
{
struct Options;

/// Reads INPUT by its extension; returns the algorithm producing it (Fail()s on an unknown
/// extension or a missing file).
vtkSmartPointer<vtkAlgorithm> MakeReader(const Options& o);

} // namespace avcli

#endif
