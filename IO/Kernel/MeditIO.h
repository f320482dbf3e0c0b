// SPDX-License-Identifier: BSD-3-Clause
// MeditIO: VTK-free reader/writer for the Medit ASCII mesh (.mesh) and solution (.sol)
// formats used by MMG, Gmsh, FreeFEM, Feflow, ...
#ifndef av_MeditIO_h
#define av_MeditIO_h

#include "SimplexMesh.h"

#include <cstdint>
#include <string>
#include <vector>

namespace av
{

/**
 * Content of a Medit .mesh file.
 *
 * Mesh holds the highest-dimensional simplices: the tetrahedra if the file has any,
 * otherwise the triangles (a 2D domain for `Dimension 2`, a surface for `Dimension 3`).
 * When tetrahedra are present the triangles are kept separately as (boundary) faces, and
 * edges are always kept separately, so a read + write round trip loses no simplex.
 * Corners (vertex ids) and Ridges (indices into Edges) are kept (ASCII and binary files).
 * Quadrilaterals, Hexahedra, Prisms, Required*, Normals, Tangents and any other keyword are
 * skipped; their names are listed in IgnoredKeywords. All ids are 0-based (the file is 1-based).
 */
struct MeditMesh
{
  SimplexMesh Mesh;
  std::vector<std::int32_t> PointRefs; ///< one per vertex
  std::vector<std::int32_t> CellRefs;  ///< one per cell of Mesh
  std::vector<std::int32_t> Faces;     ///< triangles (3 ids) when Mesh holds tetrahedra
  std::vector<std::int32_t> FaceRefs;
  std::vector<std::int32_t> Edges; ///< 2 ids per edge
  std::vector<std::int32_t> EdgeRefs;
  std::vector<std::int32_t> Corners;        ///< vertex ids (MMG's geometric corners)
  std::vector<std::int32_t> Ridges;         ///< indices into Edges (MMG's ridges: sharp edges)
  int Version = 2;                          ///< MeshVersionFormatted value
  std::vector<std::string> IgnoredKeywords; ///< keywords found but not kept
};

/**
 * Content of a Medit .sol file (`SolAtVertices` only).
 * Field types: 1 scalar, 2 vector (Dimension values), 3 symmetric tensor.
 * Tensor fields are stored here in VTK order (XX, YY, ZZ, XY, YZ, XZ; 6 values per vertex,
 * also in 2D where ZZ = YZ = XZ = 0). The file order is Medit's lower triangle row by row:
 * 3D m11 m21 m22 m31 m32 m33, 2D m11 m21 m22. Scalars hold 1 value, vectors Dimension values.
 */
struct MeditSol
{
  int Dimension = 3;
  std::size_t NumVertices = 0;
  std::vector<int> FieldTypes;
  std::vector<std::vector<double>> Fields; ///< per field: NumVertices x FieldComponents(type)

  /// Values stored per vertex in Fields for a field type (1, Dimension or 6).
  int FieldComponents(int type) const { return type == 1 ? 1 : (type == 2 ? Dimension : 6); }
};

/// Parses Medit .mesh text. `sourceName` only appears in error messages.
/// Throws InputError (with the line number and what was expected) on any malformed input.
MeditMesh ParseMeditMesh(const std::string& text, const std::string& sourceName = "<string>");
/// Reads an ASCII .mesh file (binary .meshb is rejected with an InputError).
MeditMesh ReadMeditMesh(const std::string& fileName);

/// Formats a mesh as Medit text (MeshVersionFormatted 2, doubles written exactly).
std::string FormatMeditMesh(const MeditMesh& mesh);
/// Convenience: a bare SimplexMesh with optional per-point / per-cell refs (else 0).
std::string FormatMeditMesh(const SimplexMesh& mesh,
                            const std::int32_t* pointRefs = nullptr,
                            const std::int32_t* cellRefs = nullptr);
/// Writes FormatMeditMesh(mesh) to a file; throws InputError if it cannot be written.
void WriteMeditMesh(const std::string& fileName, const MeditMesh& mesh);

/// Parses Medit .sol text (SolAtVertices). Tensors are converted to VTK order.
MeditSol ParseMeditSol(const std::string& text, const std::string& sourceName = "<string>");
/// Reads an ASCII .sol file.
MeditSol ReadMeditSol(const std::string& fileName);
/// Formats a solution as Medit text; tensors are converted back to Medit order.
std::string FormatMeditSol(const MeditSol& sol);
/// Writes FormatMeditSol(sol) to a file; throws InputError if it cannot be written.
void WriteMeditSol(const std::string& fileName, const MeditSol& sol);

/**
 * Turns field `field` of a .sol into a MetricField (VTK order, 6 values per vertex).
 * A scalar field is a size h (MMG/Medit convention) and becomes M = I / h^2 (h must be
 * finite and > 0; in 2D ZZ is 0); a tensor field is copied. Vector fields are rejected.
 * No SPD check here: on surfaces a metric may legitimately be rank 2.
 */
MetricField MetricFromMeditSol(const MeditSol& sol, std::size_t field = 0);
/// A one-field tensor (type 3) .sol from a metric; dimension 2 writes XX, XY, YY only.
MeditSol MeditSolFromMetric(const MetricField& metric, int dimension);

/// VTK-order 6-tensor from Medit lower-triangle order (3 values in 2D, 6 in 3D).
void MeditTensorToVTK(int dimension, const double* medit, double vtk[6]);
/// Medit lower-triangle order (3 values in 2D, 6 in 3D) from a VTK-order 6-tensor.
void VTKTensorToMedit(int dimension, const double vtk[6], double* medit);

} // namespace av

#endif
