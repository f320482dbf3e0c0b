// SPDX-License-Identifier: BSD-3-Clause
// OffReader: Object File Format (.off) triangle/polygon surfaces, for the CLI. VTK-free.
#ifndef av_OffReader_h
#define av_OffReader_h

#include "SimplexMesh.h"

#include <string>

namespace av
{
/**
 * Parses an ASCII OFF surface ("OFF", counts "nv nf ne", nv lines "x y z", nf lines
 * "n i0 ... i(n-1) [color]"; '#' comments; the header may share the counts' line). Polygons
 * are fanned into triangles. Returns a SimplexMesh with AmbientDim 3, SimplexDim 2. Throws
 * InputError naming the line for a truncated file, a bad token, a NaN, an index out of range,
 * a face with fewer than 3 vertices or counts larger than the file can hold.
 */
SimplexMesh ParseOff(const std::string& text, const std::string& sourceName = "<string>");

/// Reads and parses a file (InputError when it cannot be opened).
SimplexMesh ReadOff(const std::string& fileName);
}

#endif
