// SPDX-License-Identifier: BSD-3-Clause
// FrdReader: VTK-free reader for CalculiX / cgx ASCII result files (.frd).
#ifndef av_FrdReader_h
#define av_FrdReader_h

#include "SimplexMesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace av
{

/// Element type codes of the frd format.
enum FrdElementType
{
  FrdHe8 = 1,
  FrdPe6 = 2,
  FrdTe4 = 3,
  FrdHe20 = 4,
  FrdPe15 = 5,
  FrdTe10 = 6,
  FrdTr3 = 7,
  FrdTr6 = 8,
  FrdQu4 = 9,
  FrdQu8 = 10,
  FrdBe2 = 11,
  FrdBe3 = 12
};

/// Number of nodes of an frd element type (0 for an unknown type).
int FrdNodesPerElement(int type);
/// Number of corner (vertex) nodes; the corners are always the first nodes of an element.
int FrdCornersPerElement(int type);
/**
 * Node permutation from frd to VTK order: VTK node i is frd node FrdToVTKNodeOrder(type)[i].
 * Linear types except pe6, and te10, tr6, qu8, be3 are identical. he20: frd (cgx) lists the
 * bottom mid-edge nodes, then the vertical ones, then the top ones, while VTK (and the
 * CalculiX input deck) lists bottom, top, vertical; checked geometrically on the CalculiX
 * example result.frd. Wedges (pe6, pe15): CalculiX orients the (0,1,2) face towards (3,4,5),
 * VTK away from it, so VTK's base is frd's top face (and the pe15 mid-edge nodes follow).
 * Returns nullptr for an unknown type.
 */
const int* FrdToVTKNodeOrder(int type);

/// VTK's cell type id of an frd element type (numeric: 12 hexahedron, 25 quadratic
/// hexahedron, ...; see the table in IO/README.md), 0 (VTK_EMPTY_CELL) for an unknown type.
int FrdToVTKCellType(int type);

/**
 * One result block (`100C`) of an frd file: one named nodal field of one step.
 *
 * Symmetric tensors (all components of type 4, e.g. STRESS: SXX SYY SZZ SXY SYZ SZX, or
 * TOSTRAIN) are reordered by their (row, column) indices into VTK order XX YY ZZ XY YZ XZ
 * (note: frd's SZX is XZ). 3-component vectors (type 2, e.g. DISP D1 D2 D3) are ordered
 * by their index. Derived components the file does not store (`ALL`) are dropped.
 * Nodes absent from the block get 0.
 */
struct FrdResult
{
  std::string Name;                        ///< e.g. "DISP", "STRESS"
  int Step = 0;                            ///< NUMSTP of the 100C line (mode / increment)
  double Value = 0.0;                      ///< VALUE of the 100C line (time, frequency)
  std::string Analysis;                    ///< e.g. "MODAL", "STATIC" (may be empty)
  std::vector<std::string> ComponentNames; ///< in stored order
  int NumComponents = 0;
  bool IsVector = false;
  bool IsSymmetricTensor = false; ///< 6 components in VTK order
  std::vector<double> Values;     ///< NumNodes x NumComponents, by 0-based node index
  std::size_t Line = 0;           ///< line of the 100C header, for messages
};

/// Content of an frd file. Node and element ids of the file are mapped to 0-based indices.
struct FrdData
{
  std::vector<double> Points;        ///< NumNodes x 3
  std::vector<std::int32_t> NodeIds; ///< original node id of each node
  std::vector<std::int32_t> ElementIds, ElementTypes, ElementGroups, ElementMaterials;
  std::vector<std::int64_t> Offsets;      ///< NumElements + 1 offsets into Connectivity
  std::vector<std::int32_t> Connectivity; ///< 0-based node indices, frd node order
  std::vector<std::uint8_t> IsCornerNode; ///< per node: 1 if it is a corner of some element
  std::vector<FrdResult> Results;         ///< in file order

  std::size_t NumNodes() const { return NodeIds.size(); }
  std::size_t NumElements() const { return ElementIds.size(); }
  /// Distinct Step numbers of Results, in file order.
  std::vector<int> Steps() const;
  /// Index in Results of block `name` at step `step`, or -1.
  int FindResult(const std::string& name, int step) const;
};

/// Parses frd text (ASCII, short or long format). Fields are read by their fixed columns,
/// so glued numbers such as "-1.2E+00-2.3E+00" are fine. Throws InputError naming the line.
FrdData ParseFrd(const std::string& text, const std::string& sourceName = "<string>");
/// Reads an .frd file (binary frd is rejected with an InputError).
FrdData ReadFrd(const std::string& fileName);

} // namespace av

#endif
