// SPDX-License-Identifier: BSD-3-Clause
#include "MeditIO.h"

#include "FileBytes.h"
#include "MeditBinaryIO.h"
#include "MeditSectionCount.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>

namespace av
{
namespace
{

bool IEquals(std::string_view a, const char* b)
{
  const std::size_t n = std::strlen(b);
  if (a.size() != n)
  {
    return false;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const char x = a[i] >= 'A' && a[i] <= 'Z' ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
    const char y = b[i] >= 'A' && b[i] <= 'Z' ? static_cast<char>(b[i] - 'A' + 'a') : b[i];
    if (x != y)
    {
      return false;
    }
  }
  return true;
}

bool LooksNumeric(std::string_view t)
{
  const char c = t.empty() ? 'x' : t[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

std::string Printable(std::string_view t)
{
  std::string s(t.substr(0, 40));
  for (char& c : s)
  {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126)
    {
      c = '?';
    }
  }
  return t.size() > 40 ? s + "..." : s;
}

/// Whitespace tokenizer over the whole text that knows the line of every token and skips
/// '#' comments. All parse errors go through Fail() so they name the source and line.
class Tokenizer
{
public:
  Tokenizer(const std::string& text, const std::string& source)
    : Text(text)
    , Source(source)
  {
  }

  /// Next token, or an empty view at end of input. TokenLine is set to its line.
  std::string_view Next()
  {
    this->SkipBlanks();
    this->TokenLine = this->Line;
    const std::size_t start = this->Pos;
    while (this->Pos < this->Text.size() && !IsBlank(this->Text[this->Pos]) &&
           this->Text[this->Pos] != '#')
    {
      ++this->Pos;
    }
    return std::string_view(this->Text).substr(start, this->Pos - start);
  }

  std::string_view Peek()
  {
    const std::size_t pos = this->Pos, line = this->Line, tokLine = this->TokenLine;
    const std::string_view t = this->Next();
    this->Pos = pos;
    this->Line = line;
    this->TokenLine = tokLine;
    return t;
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw InputError(this->Source + ":" + std::to_string(this->TokenLine) + ": " + what);
  }

  std::string Got(std::string_view t) const
  {
    return t.empty() ? std::string("end of file") : "'" + Printable(t) + "'";
  }

  std::int64_t Int(const char* expected, std::int64_t lo, std::int64_t hi)
  {
    std::string_view t = this->Next();
    std::int64_t v = 0;
    if (!t.empty() && t[0] == '+')
    {
      t.remove_prefix(1);
    }
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
    {
      this->Fail(std::string("expected ") + expected + " (an integer), got " + this->Got(t));
    }
    if (v < lo || v > hi)
    {
      this->Fail(std::string("expected ") + expected + " in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "], got " + std::to_string(v));
    }
    return v;
  }

  double Real(const char* expected)
  {
    std::string_view t = this->Next();
    if (!t.empty() && t[0] == '+')
    {
      t.remove_prefix(1);
    }
    double v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
    {
      this->Fail(std::string("expected ") + expected + " (a number), got " + this->Got(t));
    }
    if (!std::isfinite(v))
    {
      this->Fail(std::string("expected ") + expected + " (a finite number), got " + this->Got(t));
    }
    return v;
  }

  /// Reads a section count that the rest of the file can hold (MeditSectionCountError), each
  /// entry `tokensEach` tokens.
  std::size_t Count(const char* section, std::size_t tokensEach)
  {
    const std::int64_t n = this->Int((std::string("the number of ") + section).c_str(),
                                     0,
                                     std::numeric_limits<std::int32_t>::max());
    const std::string error = MeditSectionCountError(
      section, n, MeditTextEntryBytes(tokensEach), this->BytesLeft(), /*lastEntrySlack=*/1);
    if (!error.empty())
    {
      this->Fail(error);
    }
    return static_cast<std::size_t>(n);
  }

  std::size_t BytesLeft() const { return this->Text.size() - this->Pos; }

  std::size_t TokenLine = 1;

private:
  static bool IsBlank(char c)
  {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
  }

  void SkipBlanks()
  {
    while (this->Pos < this->Text.size())
    {
      const char c = this->Text[this->Pos];
      if (c == '\n')
      {
        ++this->Line;
        ++this->Pos;
      }
      else if (c == '#')
      {
        while (this->Pos < this->Text.size() && this->Text[this->Pos] != '\n')
        {
          ++this->Pos;
        }
      }
      else if (IsBlank(c))
      {
        ++this->Pos;
      }
      else
      {
        break;
      }
    }
  }

  const std::string& Text;
  const std::string& Source;
  std::size_t Pos = 0;
  std::size_t Line = 1;
};

void RejectBinary(const std::string& text, const std::string& fileName)
{
  if (IsMeditBinary(text))
  {
    throw InputError(fileName +
                     ": binary Medit files (.meshb/.solb) are not supported; "
                     "convert to ASCII .mesh/.sol");
  }
}

/// Shortest text that reads back to exactly the same double.
void AppendDouble(std::string& out, double v)
{
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

void AppendInt(std::string& out, std::int64_t v)
{
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

/// Reads `count` simplices of `k` 1-based vertex ids + a ref. Ids are checked against
/// numVertices now when it is known (>= 0), else later by CheckIds.
void ReadSimplices(Tokenizer& tok,
                   const char* section,
                   int k,
                   std::int64_t numVertices,
                   std::vector<std::int32_t>& ids,
                   std::vector<std::int32_t>& refs)
{
  const std::size_t n = tok.Count(section, static_cast<std::size_t>(k + 1));
  const std::int64_t hi = numVertices >= 0 ? numVertices : std::numeric_limits<std::int32_t>::max();
  const std::string what = std::string("a vertex id of ") + section + " (1-based)";
  ids.reserve(ids.size() + n * k);
  refs.reserve(refs.size() + n);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int j = 0; j < k; ++j)
    {
      ids.push_back(static_cast<std::int32_t>(tok.Int(what.c_str(), 1, hi) - 1));
    }
    refs.push_back(
      static_cast<std::int32_t>(tok.Int((std::string("the reference of ") + section).c_str(),
                                        std::numeric_limits<std::int32_t>::min(),
                                        std::numeric_limits<std::int32_t>::max())));
  }
}

/// Reads a list section of `count` 1-based indices (Corners: vertices, Ridges: edges), checked
/// against their range at the end (FinishMeditMesh).
void ReadIndices(Tokenizer& tok, const char* section, std::vector<std::int32_t>& out)
{
  const std::size_t n = tok.Count(section, 1);
  const std::string what = std::string("an index of ") + section + " (1-based)";
  out.reserve(out.size() + n);
  for (std::size_t i = 0; i < n; ++i)
    out.push_back(static_cast<std::int32_t>(
      tok.Int(what.c_str(), 1, std::numeric_limits<std::int32_t>::max()) - 1));
}

void CheckIds(const std::vector<std::int32_t>& ids,
              std::size_t numVertices,
              const char* section,
              std::size_t sectionLine,
              int k,
              const std::string& source)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (static_cast<std::size_t>(ids[i]) >= numVertices)
    {
      throw InputError(source + ":" + std::to_string(sectionLine) + ": " + section + " entry " +
                       std::to_string(i / k + 1) + " uses vertex " + std::to_string(ids[i] + 1) +
                       " but there are only " + std::to_string(numVertices) + " vertices");
    }
  }
}

/// Skips the numbers that follow an unknown keyword.
void SkipNumbers(Tokenizer& tok)
{
  while (true)
  {
    const std::string_view t = tok.Peek();
    if (t.empty() || !LooksNumeric(t))
    {
      return;
    }
    tok.Next();
  }
}

} // namespace

void MeditTensorToVTK(int dimension, const double* m, double vtk[6])
{
  if (dimension == 2)
  { // m11 m21 m22
    vtk[0] = m[0];
    vtk[1] = m[2];
    vtk[2] = 0.0;
    vtk[3] = m[1];
    vtk[4] = 0.0;
    vtk[5] = 0.0;
  }
  else
  { // m11 m21 m22 m31 m32 m33 -> XX YY ZZ XY YZ XZ
    vtk[0] = m[0];
    vtk[1] = m[2];
    vtk[2] = m[5];
    vtk[3] = m[1];
    vtk[4] = m[4];
    vtk[5] = m[3];
  }
}

void VTKTensorToMedit(int dimension, const double vtk[6], double* m)
{
  if (dimension == 2)
  {
    m[0] = vtk[0];
    m[1] = vtk[3];
    m[2] = vtk[1];
  }
  else
  {
    m[0] = vtk[0];
    m[1] = vtk[3];
    m[2] = vtk[1];
    m[3] = vtk[5];
    m[4] = vtk[4];
    m[5] = vtk[2];
  }
}

namespace
{
/// What ParseMeditMesh has read so far.
struct MeditMeshSections
{
  int Dim = 0;
  bool HaveVertices = false;
  std::vector<double> Points;
  std::vector<std::int32_t> Tris, TriRefs, Tets, TetRefs;
  /// Section start lines for ids that could not be checked when read (vertices came later).
  std::size_t TriLine = 0, TetLine = 0, EdgeLine = 0;
  std::size_t CornerLine = 0, RidgeLine = 0; ///< checked at the end (edges may come later)
};

/// The 'Vertices' section: coordinates and references.
void ReadVertices(Tokenizer& tok, MeditMeshSections& m, MeditMesh& out)
{
  if (m.Dim == 0)
  {
    tok.Fail("'Vertices' before 'Dimension'");
  }
  if (m.HaveVertices)
  {
    tok.Fail("a second 'Vertices' section");
  }
  const std::size_t n = tok.Count("Vertices", static_cast<std::size_t>(m.Dim + 1));
  m.Points.reserve(n * m.Dim);
  out.PointRefs.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int d = 0; d < m.Dim; ++d)
    {
      m.Points.push_back(tok.Real("a vertex coordinate"));
    }
    out.PointRefs.push_back(static_cast<std::int32_t>(tok.Int("the reference of a vertex",
      std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max())));
  }
  m.HaveVertices = true;
}

/// Quadrilaterals, Hexahedra, Prisms: read (so that their numbers are checked) and ignored.
void SkipNonSimplices(Tokenizer& tok, std::string_view kw, MeditMesh& out)
{
  const int k = IEquals(kw, "Quadrilaterals") ? 4 : (IEquals(kw, "Hexahedra") ? 8 : 6);
  const std::string name(kw);
  const std::size_t n = tok.Count(name.c_str(), static_cast<std::size_t>(k + 1));
  for (std::size_t i = 0; i < n * (k + 1); ++i)
  {
    tok.Int((std::string("an integer of ") + name).c_str(),
      std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
  }
  out.IgnoredKeywords.push_back(name);
}

/// A section read before 'Vertices' has its ids checked at the end (from its first line); a
/// later repeat of the section must not cancel that check (found by FuzzMeditMesh: a second
/// 'Tetrahedra' after 'Vertices' let ids of the first one through unchecked).
void DeferIdCheck(bool haveVertices, std::size_t keywordLine, std::size_t& checkLine)
{
  if (!haveVertices && checkLine == 0)
  {
    checkLine = keywordLine;
  }
}

/// Checks the ids read before the vertices, and makes tetrahedra (with triangles as boundary
/// faces) or triangles the cells of the mesh.
void FinishMeditMesh(MeditMeshSections& m, const std::string& sourceName, MeditMesh& out)
{
  const std::size_t nv = out.PointRefs.size();
  if (m.TriLine)
  {
    CheckIds(m.Tris, nv, "Triangles", m.TriLine, 3, sourceName);
  }
  if (m.TetLine)
  {
    CheckIds(m.Tets, nv, "Tetrahedra", m.TetLine, 4, sourceName);
  }
  if (m.EdgeLine)
  {
    CheckIds(out.Edges, nv, "Edges", m.EdgeLine, 2, sourceName);
  }
  if (m.CornerLine)
  {
    CheckIds(out.Corners, nv, "Corners", m.CornerLine, 1, sourceName);
  }
  if (m.RidgeLine)
  {
    CheckIds(out.Ridges, out.Edges.size() / 2, "Ridges (edge indices)", m.RidgeLine, 1, sourceName);
  }
  out.Mesh.AmbientDim = m.Dim;
  out.Mesh.Points = std::move(m.Points);
  if (!m.TetRefs.empty())
  {
    if (m.Dim != 3)
    {
      throw InputError(sourceName + ": Tetrahedra in a 'Dimension 2' mesh");
    }
    out.Mesh.SimplexDim = 3;
    out.Mesh.Cells = std::move(m.Tets);
    out.CellRefs = std::move(m.TetRefs);
    out.Faces = std::move(m.Tris);
    out.FaceRefs = std::move(m.TriRefs);
  }
  else if (!m.TriRefs.empty())
  {
    out.Mesh.SimplexDim = 2;
    out.Mesh.Cells = std::move(m.Tris);
    out.CellRefs = std::move(m.TriRefs);
  }
  else
  {
    throw InputError(sourceName + ": the mesh has neither Tetrahedra nor Triangles");
  }
}
} // namespace

MeditMesh ParseMeditMesh(const std::string& text, const std::string& sourceName)
{
  Tokenizer tok(text, sourceName);
  MeditMesh out;
  MeditMeshSections m;
  bool haveEnd = false;
  for (std::string_view kw = tok.Next(); !kw.empty(); kw = tok.Next())
  {
    const std::size_t kwLine = tok.TokenLine;
    const std::int64_t nv = m.HaveVertices ? static_cast<std::int64_t>(out.PointRefs.size()) : -1;
    if (IEquals(kw, "MeshVersionFormatted"))
    {
      out.Version = static_cast<int>(tok.Int("the MeshVersionFormatted value", 1, 4));
    }
    else if (IEquals(kw, "Dimension"))
    {
      // A second, different Dimension would reinterpret the coordinates already read (found
      // by FuzzMeditMesh: 'Dimension 2' after 3D vertices gave a mesh of inconsistent size).
      const int dim = static_cast<int>(tok.Int("the Dimension value", 2, 3));
      if (m.Dim != 0 && dim != m.Dim)
      {
        tok.Fail("a second 'Dimension' (" + std::to_string(dim) + ") contradicts the first (" +
          std::to_string(m.Dim) + ")");
      }
      m.Dim = dim;
    }
    else if (IEquals(kw, "Vertices"))
    {
      ReadVertices(tok, m, out);
    }
    else if (IEquals(kw, "Triangles"))
    {
      DeferIdCheck(m.HaveVertices, kwLine, m.TriLine);
      ReadSimplices(tok, "Triangles", 3, nv, m.Tris, m.TriRefs);
    }
    else if (IEquals(kw, "Tetrahedra"))
    {
      DeferIdCheck(m.HaveVertices, kwLine, m.TetLine);
      ReadSimplices(tok, "Tetrahedra", 4, nv, m.Tets, m.TetRefs);
    }
    else if (IEquals(kw, "Edges"))
    {
      DeferIdCheck(m.HaveVertices, kwLine, m.EdgeLine);
      ReadSimplices(tok, "Edges", 2, nv, out.Edges, out.EdgeRefs);
    }
    else if (IEquals(kw, "Corners"))
    {
      m.CornerLine = m.CornerLine ? m.CornerLine : kwLine;
      ReadIndices(tok, "Corners", out.Corners);
    }
    else if (IEquals(kw, "Ridges"))
    {
      m.RidgeLine = m.RidgeLine ? m.RidgeLine : kwLine;
      ReadIndices(tok, "Ridges", out.Ridges);
    }
    else if (IEquals(kw, "Quadrilaterals") || IEquals(kw, "Hexahedra") || IEquals(kw, "Prisms"))
    {
      SkipNonSimplices(tok, kw, out);
    }
    else if (IEquals(kw, "End"))
    {
      haveEnd = true;
      break;
    }
    else if (!LooksNumeric(kw))
    {
      out.IgnoredKeywords.emplace_back(kw);
      SkipNumbers(tok);
    }
    else
    {
      tok.Fail("expected a keyword (Vertices, Triangles, Tetrahedra, Edges, End, ...), got " +
        tok.Got(kw));
    }
  }
  if (!haveEnd)
  {
    throw InputError(sourceName + ": no 'End' keyword: the file is truncated or not a Medit mesh");
  }
  if (!m.HaveVertices)
  {
    throw InputError(sourceName + ": no 'Vertices' section");
  }
  FinishMeditMesh(m, sourceName, out);
  return out;
}

MeditMesh ReadMeditMesh(const std::string& fileName)
{
  const std::string text = ReadFileBytes(fileName);
  RejectBinary(text, fileName);
  return ParseMeditMesh(text, fileName);
}

namespace
{
void AppendSimplices(std::string& s,
                     const char* name,
                     const std::vector<std::int32_t>& ids,
                     const std::vector<std::int32_t>* refs,
                     int k,
                     std::size_t numPoints)
{
  const std::size_t n = ids.size() / k;
  if (n == 0)
  {
    return;
  }
  if (ids.size() % k != 0 || (refs && !refs->empty() && refs->size() != n))
  {
    throw InputError(std::string("Medit writer: inconsistent ") + name + " array sizes");
  }
  s += "\n";
  s += name;
  s += "\n";
  AppendInt(s, static_cast<std::int64_t>(n));
  s += "\n";
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int j = 0; j < k; ++j)
    {
      const std::int32_t id = ids[i * k + j];
      if (id < 0 || static_cast<std::size_t>(id) >= numPoints)
      {
        throw InputError(std::string("Medit writer: ") + name + " " + std::to_string(i) +
                         " uses point " + std::to_string(id) + " of " + std::to_string(numPoints));
      }
      AppendInt(s, id + 1);
      s += ' ';
    }
    AppendInt(s, refs && !refs->empty() ? (*refs)[i] : 0);
    s += '\n';
  }
}
} // namespace

namespace
{
/// A list section of 1-based indices below `limit` (Corners: vertices, Ridges: edges).
void AppendIndices(std::string& s,
  const char* name,
  const std::vector<std::int32_t>& ids,
  std::size_t limit)
{
  if (ids.empty())
    return;
  s += "\n";
  s += name;
  s += "\n";
  AppendInt(s, static_cast<std::int64_t>(ids.size()));
  s += "\n";
  for (std::int32_t id : ids)
  {
    if (id < 0 || static_cast<std::size_t>(id) >= limit)
      throw InputError(std::string("Medit writer: ") + name + " entry " + std::to_string(id) +
        " out of range (" + std::to_string(limit) + ")");
    AppendInt(s, id + 1);
    s += "\n";
  }
}
} // namespace

std::string FormatMeditMesh(const MeditMesh& m)
{
  const SimplexMesh& mesh = m.Mesh;
  const int dim = mesh.AmbientDim;
  if (dim != 2 && dim != 3)
  {
    throw InputError("Medit writer: AmbientDim must be 2 or 3, got " + std::to_string(dim));
  }
  if (mesh.SimplexDim != 2 && mesh.SimplexDim != 3)
  {
    throw InputError("Medit writer: SimplexDim must be 2 or 3, got " +
                     std::to_string(mesh.SimplexDim));
  }
  if (mesh.SimplexDim == 3 && dim != 3)
  {
    throw InputError("Medit writer: tetrahedra need AmbientDim 3");
  }
  if (mesh.SimplexDim == 2 && !m.Faces.empty())
  {
    throw InputError("Medit writer: Faces are only allowed next to tetrahedra");
  }
  const std::size_t np = mesh.NumPoints();
  if (mesh.Points.size() != np * dim || (!m.PointRefs.empty() && m.PointRefs.size() != np))
  {
    throw InputError("Medit writer: inconsistent point array sizes");
  }
  std::string s;
  s.reserve(np * dim * 24 + mesh.Cells.size() * 8 + 128);
  s += "MeshVersionFormatted 2\n\nDimension ";
  AppendInt(s, dim);
  s += "\n\nVertices\n";
  AppendInt(s, static_cast<std::int64_t>(np));
  s += '\n';
  for (std::size_t i = 0; i < np; ++i)
  {
    for (int d = 0; d < dim; ++d)
    {
      const double v = mesh.Points[i * dim + d];
      if (!std::isfinite(v))
      {
        throw InputError("Medit writer: point " + std::to_string(i) +
                         " has a non-finite coordinate");
      }
      AppendDouble(s, v);
      s += ' ';
    }
    AppendInt(s, m.PointRefs.empty() ? 0 : m.PointRefs[i]);
    s += '\n';
  }
  if (mesh.SimplexDim == 3)
  {
    AppendSimplices(s, "Tetrahedra", mesh.Cells, &m.CellRefs, 4, np);
    AppendSimplices(s, "Triangles", m.Faces, &m.FaceRefs, 3, np);
  }
  else
  {
    AppendSimplices(s, "Triangles", mesh.Cells, &m.CellRefs, 3, np);
  }
  AppendSimplices(s, "Edges", m.Edges, &m.EdgeRefs, 2, np);
  AppendIndices(s, "Corners", m.Corners, np);
  AppendIndices(s, "Ridges", m.Ridges, m.Edges.size() / 2);
  s += "\nEnd\n";
  return s;
}

std::string FormatMeditMesh(const SimplexMesh& mesh,
                            const std::int32_t* pointRefs,
                            const std::int32_t* cellRefs)
{
  MeditMesh m;
  m.Mesh = mesh;
  if (pointRefs)
  {
    m.PointRefs.assign(pointRefs, pointRefs + mesh.NumPoints());
  }
  if (cellRefs)
  {
    m.CellRefs.assign(cellRefs, cellRefs + mesh.NumCells());
  }
  return FormatMeditMesh(m);
}

void WriteMeditMesh(const std::string& fileName, const MeditMesh& mesh)
{
  WriteFileBytes(fileName, FormatMeditMesh(mesh));
}

MeditSol ParseMeditSol(const std::string& text, const std::string& sourceName)
{
  Tokenizer tok(text, sourceName);
  MeditSol sol;
  int dim = 0;
  bool haveSol = false, haveEnd = false;
  for (std::string_view kw = tok.Next(); !kw.empty(); kw = tok.Next())
  {
    if (IEquals(kw, "MeshVersionFormatted"))
    {
      tok.Int("the MeshVersionFormatted value", 1, 4);
    }
    else if (IEquals(kw, "Dimension"))
    {
      dim = static_cast<int>(tok.Int("the Dimension value", 2, 3));
    }
    else if (IEquals(kw, "SolAtVertices"))
    {
      if (dim == 0)
      {
        tok.Fail("'SolAtVertices' before 'Dimension'");
      }
      if (haveSol)
      {
        tok.Fail("a second 'SolAtVertices' section");
      }
      sol.Dimension = dim;
      const std::int64_t n = tok.Int(
        "the number of vertices of SolAtVertices", 0, std::numeric_limits<std::int32_t>::max());
      const int nf = static_cast<int>(tok.Int("the number of solution fields", 1, 64));
      std::size_t perVertex = 0; // values per vertex in the file
      for (int f = 0; f < nf; ++f)
      {
        const int type =
          static_cast<int>(tok.Int("a field type (1 scalar, 2 vector, 3 symmetric tensor)", 1, 3));
        sol.FieldTypes.push_back(type);
        perVertex += type == 1 ? 1 : (type == 2 ? dim : dim * (dim + 1) / 2);
      }
      const std::string error = MeditSectionCountError(
        "SolAtVertices (" + std::to_string(perVertex) + " values per vertex)",
        n,
        MeditTextEntryBytes(perVertex),
        tok.BytesLeft(),
        /*lastEntrySlack=*/1);
      if (!error.empty())
      {
        tok.Fail(error);
      }
      sol.NumVertices = static_cast<std::size_t>(n);
      sol.Fields.resize(nf);
      for (int f = 0; f < nf; ++f)
      {
        sol.Fields[f].reserve(sol.NumVertices * sol.FieldComponents(sol.FieldTypes[f]));
      }
      double buf[6];
      for (std::size_t i = 0; i < sol.NumVertices; ++i)
      {
        for (int f = 0; f < nf; ++f)
        {
          const int type = sol.FieldTypes[f];
          std::vector<double>& out = sol.Fields[f];
          if (type == 3)
          {
            const int k = dim * (dim + 1) / 2;
            for (int j = 0; j < k; ++j)
            {
              buf[j] = tok.Real("a tensor component of SolAtVertices");
            }
            double vtk[6];
            MeditTensorToVTK(dim, buf, vtk);
            out.insert(out.end(), vtk, vtk + 6);
          }
          else
          {
            const int k = type == 1 ? 1 : dim;
            for (int j = 0; j < k; ++j)
            {
              out.push_back(tok.Real(type == 1 ? "a scalar of SolAtVertices"
                                               : "a vector component of SolAtVertices"));
            }
          }
        }
      }
      haveSol = true;
    }
    else if (IEquals(kw, "End"))
    {
      haveEnd = true;
      break;
    }
    else if (!LooksNumeric(kw))
    {
      SkipNumbers(tok); // SolAtTriangles, Time, ...: not used
    }
    else
    {
      tok.Fail("expected a keyword (SolAtVertices, End, ...), got " + tok.Got(kw));
    }
  }
  if (!haveEnd)
  {
    throw InputError(sourceName + ": no 'End' keyword: the file is truncated or not a Medit .sol");
  }
  if (!haveSol)
  {
    throw InputError(sourceName + ": no 'SolAtVertices' section");
  }
  return sol;
}

MeditSol ReadMeditSol(const std::string& fileName)
{
  const std::string text = ReadFileBytes(fileName);
  RejectBinary(text, fileName);
  return ParseMeditSol(text, fileName);
}

std::string FormatMeditSol(const MeditSol& sol)
{
  const int dim = sol.Dimension;
  if (dim != 2 && dim != 3)
  {
    throw InputError("Medit .sol writer: Dimension must be 2 or 3");
  }
  if (sol.FieldTypes.empty() || sol.FieldTypes.size() != sol.Fields.size())
  {
    throw InputError("Medit .sol writer: need at least one field and one type per field");
  }
  for (std::size_t f = 0; f < sol.Fields.size(); ++f)
  {
    const int type = sol.FieldTypes[f];
    if (type < 1 || type > 3)
    {
      throw InputError("Medit .sol writer: field type must be 1, 2 or 3");
    }
    if (sol.Fields[f].size() != sol.NumVertices * sol.FieldComponents(type))
    {
      throw InputError("Medit .sol writer: field " + std::to_string(f) + " has " +
                       std::to_string(sol.Fields[f].size()) + " values, expected " +
                       std::to_string(sol.NumVertices * sol.FieldComponents(type)));
    }
  }
  std::string s;
  s.reserve(sol.NumVertices * 6 * 24 + 128);
  s += "MeshVersionFormatted 2\n\nDimension ";
  AppendInt(s, dim);
  s += "\n\nSolAtVertices\n";
  AppendInt(s, static_cast<std::int64_t>(sol.NumVertices));
  s += '\n';
  AppendInt(s, static_cast<std::int64_t>(sol.FieldTypes.size()));
  for (int t : sol.FieldTypes)
  {
    s += ' ';
    AppendInt(s, t);
  }
  s += "\n";
  double m[6];
  for (std::size_t i = 0; i < sol.NumVertices; ++i)
  {
    for (std::size_t f = 0; f < sol.Fields.size(); ++f)
    {
      const int type = sol.FieldTypes[f];
      const int nc = sol.FieldComponents(type);
      const double* v = sol.Fields[f].data() + i * nc;
      int k = nc;
      if (type == 3)
      {
        VTKTensorToMedit(dim, v, m);
        v = m;
        k = dim * (dim + 1) / 2;
      }
      for (int j = 0; j < k; ++j)
      {
        if (!std::isfinite(v[j]))
        {
          throw InputError("Medit .sol writer: vertex " + std::to_string(i) +
                           " has a non-finite value");
        }
        AppendDouble(s, v[j]);
        s += ' ';
      }
    }
    s.back() = '\n';
  }
  s += "\nEnd\n";
  return s;
}

void WriteMeditSol(const std::string& fileName, const MeditSol& sol)
{
  WriteFileBytes(fileName, FormatMeditSol(sol));
}

MetricField MetricFromMeditSol(const MeditSol& sol, std::size_t field)
{
  if (field >= sol.Fields.size())
  {
    throw InputError("the .sol has " + std::to_string(sol.Fields.size()) + " field(s), field " +
                     std::to_string(field) + " requested");
  }
  const int type = sol.FieldTypes[field];
  const std::vector<double>& f = sol.Fields[field];
  MetricField metric;
  if (type == 3)
  {
    metric.Values = f;
    return metric;
  }
  if (type != 1)
  {
    throw InputError("a vector field of a .sol cannot be used as a metric (need a scalar size "
                     "or a symmetric tensor)");
  }
  metric.Values.assign(sol.NumVertices * 6, 0.0);
  for (std::size_t i = 0; i < sol.NumVertices; ++i)
  {
    const double h = f[i];
    if (!(h > 0.0) || !std::isfinite(h))
    {
      throw InputError("scalar .sol value at vertex " + std::to_string(i + 1) +
                       " is a size h and must be > 0, got " + std::to_string(h));
    }
    const double m = 1.0 / (h * h);
    double* v = metric.Values.data() + 6 * i;
    v[0] = v[1] = m;
    v[2] = sol.Dimension == 3 ? m : 0.0;
  }
  return metric;
}

MeditSol MeditSolFromMetric(const MetricField& metric, int dimension)
{
  if (dimension != 2 && dimension != 3)
  {
    throw InputError("MeditSolFromMetric: dimension must be 2 or 3");
  }
  if (metric.Values.size() % 6 != 0)
  {
    throw InputError("MeditSolFromMetric: the metric must hold 6 values per point");
  }
  MeditSol sol;
  sol.Dimension = dimension;
  sol.NumVertices = metric.NumPoints();
  sol.FieldTypes = { 3 };
  sol.Fields = { metric.Values };
  if (dimension == 2)
  { // only XX, YY, XY are written; drop the rest so a re-read compares equal
    for (std::size_t i = 0; i < sol.NumVertices; ++i)
    {
      double* v = sol.Fields[0].data() + 6 * i;
      v[2] = v[4] = v[5] = 0.0;
    }
  }
  return sol;
}

} // namespace av
