// SPDX-License-Identifier: BSD-3-Clause
// MeditOutput: the MMG-style output of the anisovoronoi tool, the mesh as Medit .mesh/.meshb
// and its metric as .sol/.solb, for MMG, Feflo.a and solvers.
#ifndef avcli_MeditOutput_h
#define avcli_MeditOutput_h

#include <string>

class vtkDataObject;

namespace avcli
{
class AtomicOutput;

/// The metric file next to a mesh file: out.mesh -> out.sol, out.meshb -> out.solb.
std::string SolPathFor(const std::string& meshPath);

/// Writes `mesh` (triangles / tetrahedra with the point array "Metric") to `meshPath` and its
/// metric to SolPathFor(meshPath), ASCII or binary by extension, both through `output` (temporary
/// names, renamed once complete); Fail()s with the reason.
void WriteMeditOutput(const AtomicOutput& output, vtkDataObject* mesh, const std::string& meshPath);

} // namespace avcli

#endif
