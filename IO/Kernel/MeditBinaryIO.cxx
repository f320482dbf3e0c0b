// SPDX-License-Identifier: BSD-3-Clause
#include "MeditBinaryIO.h"

#include "FileBytes.h"
#include "InputError.h"
#include "MeditSectionCount.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace av
{
namespace
{
constexpr int KwDimension = 3;
constexpr int KwVertices = 4;
constexpr int KwEdges = 5;
constexpr int KwTriangles = 6;
constexpr int KwTetrahedra = 8;
constexpr int KwCorners = 13; // libMeshb's GmfCorners: one vertex index per line
constexpr int KwRidges = 14;  // GmfRidges: one edge index per line
constexpr int KwEnd = 54;
constexpr int KwSolAtVertices = 62;

/// Bounds-checked reader of the binary words; all errors name the source and byte offset.
class Cursor
{
public:
  Cursor(const std::string& bytes, const std::string& source)
    : Bytes(bytes)
    , Source(source)
  {
    if (bytes.size() < 8)
      this->Fail("too short for a binary Medit header");
    std::int32_t code = 0;
    std::memcpy(&code, bytes.data(), 4);
    this->Swap = code != 1; // a big-endian file on this little-endian machine, or garbage
    if (this->Int32() != 1)
      this->Fail("does not start with the binary Medit code 1");
    this->Version = this->Int32();
    if (this->Version < 1 || this->Version > 4)
      this->Fail("unknown binary Medit version " + std::to_string(this->Version));
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw InputError(this->Source + ": " + what + " (byte " + std::to_string(this->Pos) + ")");
  }

  std::int32_t Int32() { return this->Word<std::int32_t>(); }
  std::int64_t Int64() { return this->Word<std::int64_t>(); }
  /// An integer of the file's width (int64 in version 4).
  std::int64_t Int() { return this->Version >= 4 ? this->Int64() : this->Int32(); }
  /// A file position (int64 from version 3).
  std::int64_t Position() { return this->Version >= 3 ? this->Int64() : this->Int32(); }
  double Real() { return this->Version == 1 ? this->Word<float>() : this->Word<double>(); }

  /// A line count that the bytes left can hold (MeditSectionCountError), each line
  /// `lineBytes` bytes.
  std::size_t Count(std::size_t lineBytes, const char* what)
  {
    const std::int64_t n = this->Int();
    this->CheckCount(n, lineBytes, what);
    return static_cast<std::size_t>(n);
  }
  /// Fails unless the bytes left can hold `n` lines of `lineBytes` bytes.
  void CheckCount(std::int64_t n, std::size_t lineBytes, const std::string& what) const
  {
    const std::string error = MeditSectionCountError(what, n, lineBytes, this->BytesLeft());
    if (!error.empty())
      this->Fail(error);
  }
  /// The Dimension keyword's value, 2 or 3.
  int Dimension()
  {
    const int dim = this->Int32();
    if (dim != 2 && dim != 3)
      this->Fail("Dimension must be 2 or 3, got " + std::to_string(dim));
    return dim;
  }
  std::size_t IntBytes() const { return this->Version >= 4 ? 8 : 4; }
  std::size_t RealBytes() const { return this->Version == 1 ? 4 : 8; }
  bool AtEnd() const { return this->Pos >= this->Bytes.size(); }
  /// Reads the next keyword's code and the position of the one after it; false at End or at
  /// the end of the bytes.
  bool NextKeyword(int& code, std::int64_t& next)
  {
    if (this->AtEnd())
      return false;
    code = this->Int32();
    if (code == KwEnd)
      return false;
    next = this->Position();
    return true;
  }
  std::size_t BytesLeft() const { return this->Bytes.size() - this->Pos; }
  void Seek(std::int64_t pos)
  {
    if (pos <= static_cast<std::int64_t>(this->Pos) ||
      pos > static_cast<std::int64_t>(this->Bytes.size()))
      this->Fail("cannot skip the keyword: bad next-keyword position " + std::to_string(pos));
    this->Pos = static_cast<std::size_t>(pos);
  }

  int Version = 0;

private:
  template <typename T>
  T Word()
  {
    if (this->Pos + sizeof(T) > this->Bytes.size())
      this->Fail("unexpected end of file");
    char raw[sizeof(T)];
    std::memcpy(raw, this->Bytes.data() + this->Pos, sizeof(T));
    if (this->Swap)
      std::reverse(raw, raw + sizeof(T));
    this->Pos += sizeof(T);
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
  }

  const std::string& Bytes;
  std::string Source;
  std::size_t Pos = 0;
  bool Swap = false;
};

/// Appends binary words of one version; Patch() fills a keyword's next-keyword position.
class Writer
{
public:
  explicit Writer(int version)
    : Version(version)
  {
    this->Int32(1);
    this->Int32(version);
  }
  void Int32(std::int32_t v) { this->Raw(&v, 4); }
  void Int(std::int64_t v)
  {
    if (this->Version >= 4)
      this->Raw(&v, 8);
    else
      this->Int32(static_cast<std::int32_t>(v));
  }
  void Real(double v) { this->Raw(&v, 8); }
  /// Starts a keyword: its code, a next-position placeholder (patched by the next keyword).
  void Keyword(int code)
  {
    this->PatchPrevious();
    this->Int32(code);
    this->PendingPos = this->Out.size();
    if (this->Version >= 3)
      this->Raw("\0\0\0\0\0\0\0\0", 8);
    else
      this->Int32(0);
  }
  std::string Finish()
  {
    this->Keyword(KwEnd);
    this->PendingPos = std::string::npos; // End keeps position 0
    return std::move(this->Out);
  }

private:
  void PatchPrevious()
  {
    if (this->PendingPos == std::string::npos)
      return;
    const std::int64_t here = static_cast<std::int64_t>(this->Out.size());
    if (this->Version >= 3)
      std::memcpy(&this->Out[this->PendingPos], &here, 8);
    else
    {
      const auto here32 = static_cast<std::int32_t>(here);
      std::memcpy(&this->Out[this->PendingPos], &here32, 4);
    }
  }
  void Raw(const void* p, std::size_t n) { this->Out.append(static_cast<const char*>(p), n); }

  int Version;
  std::string Out;
  std::size_t PendingPos = std::string::npos;
};

/// Reads `count` simplices of `nv` 1-based ids + ref into 0-based ids and refs.
void ReadSimplices(Cursor& in,
  int nv,
  std::size_t numPoints,
  const char* what,
  std::vector<std::int32_t>& ids,
  std::vector<std::int32_t>& refs)
{
  const std::size_t n = in.Count(in.IntBytes() * (nv + 1), what);
  ids.resize(n * nv);
  refs.resize(n);
  for (std::size_t c = 0; c < n; ++c)
  {
    for (int k = 0; k < nv; ++k)
    {
      const std::int64_t id = in.Int();
      if (id < 1 || static_cast<std::uint64_t>(id) > numPoints)
        in.Fail(std::string(what) + " " + std::to_string(c + 1) + " has vertex id " +
          std::to_string(id) + " outside [1, " + std::to_string(numPoints) + "]");
      ids[c * nv + k] = static_cast<std::int32_t>(id - 1);
    }
    refs[c] = static_cast<std::int32_t>(in.Int());
  }
}

/// Reads a list of `count` 1-based indices into 0-based ones; their range is checked once the
/// whole file is read (Ridges may come before Edges).
void ReadIndexList(Cursor& in, const char* what, std::vector<std::int32_t>& ids)
{
  const std::size_t n = in.Count(in.IntBytes(), what);
  ids.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::int64_t id = in.Int();
    if (id < 1 || id > std::numeric_limits<std::int32_t>::max())
      in.Fail(std::string(what) + " entry " + std::to_string(i + 1) + " is " + std::to_string(id) +
        ", not a 1-based index");
    ids[i] = static_cast<std::int32_t>(id - 1);
  }
}

/// Fails unless every id is below `limit`.
void CheckIndexRange(const std::vector<std::int32_t>& ids,
  std::size_t limit,
  const char* what,
  const std::string& sourceName)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (static_cast<std::size_t>(ids[i]) >= limit)
      throw InputError(sourceName + ": " + what + " entry " + std::to_string(i + 1) + " is " +
        std::to_string(ids[i] + 1) + ", outside [1, " + std::to_string(limit) + "]");
}

int SymmetricSize(int dim)
{
  return dim * (dim + 1) / 2;
}

/// Picks the version: 2 (int32 positions) unless the file may pass 2 GB.
int VersionFor(std::size_t estimatedBytes)
{
  return estimatedBytes < (std::size_t(1) << 31) - 4096 ? 2 : 3;
}

bool EndsWith(const std::string& s, const char* suffix)
{
  const std::size_t n = std::strlen(suffix);
  if (s.size() < n)
    return false;
  for (std::size_t i = 0; i < n; ++i)
  {
    const char c = s[s.size() - n + i];
    if ((c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c) != suffix[i])
      return false;
  }
  return true;
}
} // namespace

bool IsMeditBinary(const std::string& bytes)
{
  return bytes.size() >= 4 &&
    (bytes.compare(0, 4, std::string("\1\0\0\0", 4)) == 0 ||
      bytes.compare(0, 4, std::string("\0\0\0\1", 4)) == 0);
}

MeditMesh ParseMeditMeshBinary(const std::string& bytes, const std::string& sourceName)
{
  Cursor in(bytes, sourceName);
  MeditMesh out;
  out.Version = in.Version;
  int dim = 0;
  std::vector<double> points;
  std::vector<std::int32_t> tris, triRefs, tets, tetRefs;
  bool haveTris = false, haveTets = false;
  int code = 0;
  std::int64_t next = 0;
  while (in.NextKeyword(code, next))
  {
    if (code == KwDimension)
    {
      dim = in.Dimension();
    }
    else if (code == KwVertices)
    {
      if (dim == 0)
        in.Fail("Vertices before Dimension");
      const std::size_t n = in.Count(in.RealBytes() * dim + in.IntBytes(), "Vertices");
      points.resize(n * dim);
      out.PointRefs.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        for (int d = 0; d < dim; ++d)
        {
          points[i * dim + d] = in.Real();
          if (!std::isfinite(points[i * dim + d]))
            in.Fail("vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
        }
        out.PointRefs[i] = static_cast<std::int32_t>(in.Int());
      }
    }
    else if (code == KwEdges || code == KwTriangles || code == KwTetrahedra)
    {
      const std::size_t np = points.size() / std::max(dim, 1);
      if (code == KwEdges)
        ReadSimplices(in, 2, np, "Edges", out.Edges, out.EdgeRefs);
      else if (code == KwTriangles)
        ReadSimplices(in, 3, np, "Triangles", tris, triRefs), haveTris = true;
      else
        ReadSimplices(in, 4, np, "Tetrahedra", tets, tetRefs), haveTets = true;
    }
    else if (code == KwCorners)
      ReadIndexList(in, "Corners", out.Corners);
    else if (code == KwRidges)
      ReadIndexList(in, "Ridges", out.Ridges);
    else
    {
      out.IgnoredKeywords.push_back("keyword " + std::to_string(code));
      in.Seek(next);
    }
  }
  if (dim == 0)
    throw InputError(sourceName + ": no Dimension keyword");
  CheckIndexRange(
    out.Corners, points.size() / static_cast<std::size_t>(dim), "Corners", sourceName);
  CheckIndexRange(out.Ridges, out.Edges.size() / 2, "Ridges (edge indices)", sourceName);
  out.Mesh.AmbientDim = dim;
  out.Mesh.Points = std::move(points);
  if (haveTets && !tetRefs.empty())
  {
    if (dim != 3)
      throw InputError(sourceName + ": Tetrahedra in a 'Dimension 2' mesh");
    out.Mesh.SimplexDim = 3;
    out.Mesh.Cells = std::move(tets);
    out.CellRefs = std::move(tetRefs);
    out.Faces = std::move(tris);
    out.FaceRefs = std::move(triRefs);
  }
  else if (haveTris && !triRefs.empty())
  {
    out.Mesh.SimplexDim = 2;
    out.Mesh.Cells = std::move(tris);
    out.CellRefs = std::move(triRefs);
  }
  else
    throw InputError(sourceName + ": the mesh has neither Tetrahedra nor Triangles");
  return out;
}

std::string FormatMeditMeshBinary(const MeditMesh& m)
{
  // The ASCII writer's checks (dimensions, sizes, finite points, ids in range) first.
  (void)FormatMeditMesh(m);
  const SimplexMesh& mesh = m.Mesh;
  const int dim = mesh.AmbientDim;
  const std::size_t np = mesh.NumPoints();
  const std::size_t estimate =
    64 + np * (8 * dim + 4) + (mesh.Cells.size() + m.Faces.size() + m.Edges.size()) * 8;
  Writer w(VersionFor(estimate));
  w.Keyword(KwDimension);
  w.Int32(dim);
  w.Keyword(KwVertices);
  w.Int(static_cast<std::int64_t>(np));
  for (std::size_t i = 0; i < np; ++i)
  {
    for (int d = 0; d < dim; ++d)
      w.Real(mesh.Points[i * dim + d]);
    w.Int(m.PointRefs.empty() ? 0 : m.PointRefs[i]);
  }
  auto simplices =
    [&w](
      int code, const std::vector<std::int32_t>& ids, const std::vector<std::int32_t>& refs, int nv)
  {
    const std::size_t n = ids.size() / nv;
    if (n == 0)
      return;
    w.Keyword(code);
    w.Int(static_cast<std::int64_t>(n));
    for (std::size_t c = 0; c < n; ++c)
    {
      for (int k = 0; k < nv; ++k)
        w.Int(static_cast<std::int64_t>(ids[c * nv + k]) + 1);
      w.Int(refs.size() == n ? refs[c] : 0);
    }
  };
  if (mesh.SimplexDim == 3)
  {
    simplices(KwTetrahedra, mesh.Cells, m.CellRefs, 4);
    simplices(KwTriangles, m.Faces, m.FaceRefs, 3);
  }
  else
    simplices(KwTriangles, mesh.Cells, m.CellRefs, 3);
  simplices(KwEdges, m.Edges, m.EdgeRefs, 2);
  auto indices = [&w](int code, const std::vector<std::int32_t>& ids)
  {
    if (ids.empty())
      return;
    w.Keyword(code);
    w.Int(static_cast<std::int64_t>(ids.size()));
    for (std::int32_t id : ids)
      w.Int(static_cast<std::int64_t>(id) + 1);
  };
  indices(KwCorners, m.Corners);
  indices(KwRidges, m.Ridges);
  return w.Finish();
}

MeditSol ParseMeditSolBinary(const std::string& bytes, const std::string& sourceName)
{
  Cursor in(bytes, sourceName);
  MeditSol sol;
  int dim = 0;
  bool found = false;
  int code = 0;
  std::int64_t next = 0;
  while (!found && in.NextKeyword(code, next))
  {
    if (code == KwDimension)
    {
      dim = in.Dimension();
    }
    else if (code == KwSolAtVertices)
    {
      if (dim == 0)
        in.Fail("SolAtVertices before Dimension");
      const std::int64_t n = in.Int();
      const int numTypes = in.Int32();
      if (numTypes < 1 || numTypes > 1000)
        in.Fail("bad number of solution fields " + std::to_string(numTypes));
      sol.Dimension = dim;
      std::size_t realsPerLine = 0;
      for (int f = 0; f < numTypes; ++f)
      {
        const int type = in.Int32();
        if (type < 1 || type > 3)
          in.Fail("solution field type " + std::to_string(type) +
            " (only 1 scalar, 2 vector, "
            "3 symmetric tensor)");
        sol.FieldTypes.push_back(type);
        realsPerLine += type == 1 ? 1 : (type == 2 ? dim : SymmetricSize(dim));
      }
      in.CheckCount(n,
        realsPerLine * in.RealBytes(),
        "SolAtVertices (" + std::to_string(realsPerLine) + " values per vertex)");
      sol.NumVertices = static_cast<std::size_t>(n);
      sol.Fields.resize(numTypes);
      for (int f = 0; f < numTypes; ++f)
        sol.Fields[f].resize(sol.NumVertices * sol.FieldComponents(sol.FieldTypes[f]));
      double medit[6];
      for (std::size_t i = 0; i < sol.NumVertices; ++i)
        for (int f = 0; f < numTypes; ++f)
        {
          const int type = sol.FieldTypes[f];
          double* dst = sol.Fields[f].data() + i * sol.FieldComponents(type);
          const int count = type == 1 ? 1 : (type == 2 ? dim : SymmetricSize(dim));
          for (int k = 0; k < count; ++k)
          {
            medit[k] = in.Real();
            if (!std::isfinite(medit[k]))
              in.Fail("vertex " + std::to_string(i + 1) + " has a non-finite solution value");
          }
          if (type == 3)
            MeditTensorToVTK(dim, medit, dst);
          else
            std::copy(medit, medit + count, dst);
        }
      found = true;
    }
    else
      in.Seek(next);
  }
  if (!found)
    throw InputError(sourceName + ": no SolAtVertices keyword");
  return sol;
}

std::string FormatMeditSolBinary(const MeditSol& sol)
{
  (void)FormatMeditSol(sol); // the ASCII writer's checks
  const int dim = sol.Dimension;
  std::size_t realsPerLine = 0;
  for (int type : sol.FieldTypes)
    realsPerLine += type == 1 ? 1 : (type == 2 ? dim : SymmetricSize(dim));
  Writer w(VersionFor(64 + sol.NumVertices * realsPerLine * 8));
  w.Keyword(KwDimension);
  w.Int32(dim);
  w.Keyword(KwSolAtVertices);
  w.Int(static_cast<std::int64_t>(sol.NumVertices));
  w.Int32(static_cast<std::int32_t>(sol.FieldTypes.size()));
  for (int type : sol.FieldTypes)
    w.Int32(type);
  double medit[6];
  for (std::size_t i = 0; i < sol.NumVertices; ++i)
    for (std::size_t f = 0; f < sol.Fields.size(); ++f)
    {
      const int type = sol.FieldTypes[f];
      const double* src = sol.Fields[f].data() + i * sol.FieldComponents(type);
      if (type == 3)
      {
        VTKTensorToMedit(dim, src, medit);
        for (int k = 0; k < SymmetricSize(dim); ++k)
          w.Real(medit[k]);
      }
      else
        for (int k = 0; k < sol.FieldComponents(type); ++k)
          w.Real(src[k]);
    }
  return w.Finish();
}

MeditMesh ReadMeditMeshFile(const std::string& fileName)
{
  const std::string bytes = ReadFileBytes(fileName);
  return IsMeditBinary(bytes) ? ParseMeditMeshBinary(bytes, fileName)
                              : ParseMeditMesh(bytes, fileName);
}

MeditSol ReadMeditSolFile(const std::string& fileName)
{
  const std::string bytes = ReadFileBytes(fileName);
  return IsMeditBinary(bytes) ? ParseMeditSolBinary(bytes, fileName)
                              : ParseMeditSol(bytes, fileName);
}

void WriteMeditMeshFile(const std::string& fileName, const MeditMesh& mesh)
{
  WriteFileBytes(
    fileName, EndsWith(fileName, ".meshb") ? FormatMeditMeshBinary(mesh) : FormatMeditMesh(mesh));
}

void WriteMeditSolFile(const std::string& fileName, const MeditSol& sol)
{
  WriteFileBytes(
    fileName, EndsWith(fileName, ".solb") ? FormatMeditSolBinary(sol) : FormatMeditSol(sol));
}

} // namespace av
