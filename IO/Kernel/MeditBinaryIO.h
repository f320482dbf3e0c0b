// SPDX-License-Identifier: BSD-3-Clause
// MeditBinaryIO: VTK-free reader/writer for the binary Medit formats .meshb / .solb (the
// Gamma Mesh Format of libMeshb, written by MMG, Feflo.a, Wolf, ...), plus file functions that
// pick ASCII or binary by content (reading) or by extension (writing).
#ifndef av_MeditBinaryIO_h
#define av_MeditBinaryIO_h

#include "MeditIO.h"

#include <string>

namespace av
{

/**
 * The binary layout (libMeshb's format description, version 1 to 4):
 * - int32 1 (tells the byte order; big-endian files are swapped on read), int32 version:
 *   1: float reals, int32 integers, int32 positions; 2: double reals; 3: int64 positions;
 *   4: int64 integers and line counts;
 * - then keywords: int32 code, the position of the next keyword (int32 / int64), then for a
 *   table keyword the line count and the lines; Dimension (3) holds one int32; End (54) ends.
 *   Vertices (4): Dimension reals + ref; Edges (5), Triangles (6), Tetrahedra (8): 1-based
 *   vertex ids + ref; SolAtVertices (62): count, number of fields, their types (int32), then
 *   per vertex the fields' reals (scalar 1, vector Dimension, symmetric tensor 3 in 2D / 6 in
 *   3D, lower triangle row by row as in the ASCII .sol).
 * Other keywords are skipped through their next-keyword position and listed in
 * MeditMesh::IgnoredKeywords as "keyword N".
 */

/// True when the bytes start like a .meshb/.solb (the int32 code 1, either byte order).
bool IsMeditBinary(const std::string& bytes);

/// Parses .meshb bytes into the same MeditMesh as the ASCII parser (0-based ids).
/// Throws InputError (naming `sourceName`, the keyword and the byte offset) on bad input.
MeditMesh ParseMeditMeshBinary(const std::string& bytes, const std::string& sourceName = "<bytes>");
/// The .meshb bytes of a mesh: version 2 (double reals, int32 ids), version 3 past 2 GB.
std::string FormatMeditMeshBinary(const MeditMesh& mesh);

/// Parses .solb bytes (SolAtVertices); tensors come out in VTK order as ParseMeditSol.
MeditSol ParseMeditSolBinary(const std::string& bytes, const std::string& sourceName = "<bytes>");
/// The .solb bytes of a solution (tensors back to Medit order).
std::string FormatMeditSolBinary(const MeditSol& sol);

/// Reads a .mesh or .meshb file, ASCII or binary by content.
MeditMesh ReadMeditMeshFile(const std::string& fileName);
/// Reads a .sol or .solb file, ASCII or binary by content.
MeditSol ReadMeditSolFile(const std::string& fileName);
/// Writes a mesh: binary when the name ends with .meshb, else ASCII.
void WriteMeditMeshFile(const std::string& fileName, const MeditMesh& mesh);
/// Writes a solution: binary when the name ends with .solb, else ASCII.
void WriteMeditSolFile(const std::string& fileName, const MeditSol& sol);

} // namespace av

#endif
