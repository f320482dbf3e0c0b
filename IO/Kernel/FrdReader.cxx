// SPDX-License-Identifier: BSD-3-Clause
#include "FrdReader.h"

#include "FileBytes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <unordered_map>

namespace av
{

namespace
{
// Tables indexed by frd type (0 unused).
const int NodesPerType[13] = { 0, 8, 6, 4, 20, 15, 10, 3, 6, 4, 8, 2, 3 };
const int CornersPerType[13] = { 0, 8, 6, 4, 8, 6, 4, 3, 3, 4, 4, 2, 2 };
const int Identity[20] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19 };
// frd he20: 8..11 bottom edges, 12..15 vertical edges, 16..19 top edges;
// VTK: 8..11 bottom, 12..15 top, 16..19 vertical.
const int He20ToVTK[20] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15 };
// Wedges: the (0,1,2) normal points towards (3,4,5) in CalculiX/Abaqus but away from it in
// VTK, so VTK's base is frd's top face. frd pe15 mid-edges: 6..8 bottom, 9..11 vertical,
// 12..14 top; VTK: 6..8 base (= frd top), 9..11 top (= frd bottom), 12..14 vertical.
const int Pe6ToVTK[6] = { 3, 4, 5, 0, 1, 2 };
const int Pe15ToVTK[15] = { 3, 4, 5, 0, 1, 2, 12, 13, 14, 6, 7, 8, 9, 10, 11 };
} // namespace

int FrdNodesPerElement(int type)
{
  return type >= 1 && type <= 12 ? NodesPerType[type] : 0;
}

int FrdCornersPerElement(int type)
{
  return type >= 1 && type <= 12 ? CornersPerType[type] : 0;
}

const int* FrdToVTKNodeOrder(int type)
{
  if (type == FrdHe20)
  {
    return He20ToVTK;
  }
  if (type == FrdPe15)
  {
    return Pe15ToVTK;
  }
  if (type == FrdPe6)
  {
    return Pe6ToVTK;
  }
  return FrdNodesPerElement(type) > 0 ? Identity : nullptr;
}

int FrdToVTKCellType(int type)
{
  // VTK ids: 3 line, 5 triangle, 9 quad, 10 tetra, 12 hexahedron, 13 wedge, 21 quadratic
  // edge, 22 quadratic triangle, 23 quadratic quad, 24 quadratic tetra, 25 quadratic
  // hexahedron, 26 quadratic wedge (vtkCellType.h; the kernels are VTK-free).
  static const int vtkType[13] = { 0, 12, 13, 10, 25, 26, 24, 5, 22, 9, 23, 3, 21 };
  return type >= 1 && type <= 12 ? vtkType[type] : 0;
}

std::vector<int> FrdData::Steps() const
{
  std::vector<int> steps;
  for (const FrdResult& r : this->Results)
  {
    if (std::find(steps.begin(), steps.end(), r.Step) == steps.end())
    {
      steps.push_back(r.Step);
    }
  }
  return steps;
}

int FrdData::FindResult(const std::string& name, int step) const
{
  for (std::size_t i = 0; i < this->Results.size(); ++i)
  {
    if (this->Results[i].Name == name && this->Results[i].Step == step)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}

namespace
{

std::string_view Trim(std::string_view s)
{
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
  {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t'))
  {
    s.remove_suffix(1);
  }
  return s;
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
  return s;
}

/// Line-by-line cursor; every error names the source and the current line.
class Lines
{
public:
  Lines(const std::string& text, const std::string& source)
    : Text(text)
    , Source(source)
  {
  }

  bool Next()
  {
    if (this->Pos >= this->Text.size())
    {
      return false;
    }
    const std::size_t end = std::min(this->Text.find('\n', this->Pos), this->Text.size());
    std::string_view l(this->Text.data() + this->Pos, end - this->Pos);
    if (!l.empty() && l.back() == '\r')
    {
      l.remove_suffix(1);
    }
    this->Cur = l;
    this->Pos = end + 1;
    ++this->LineNo;
    return true;
  }

  std::size_t BytesLeft() const
  {
    return this->Pos < this->Text.size() ? this->Text.size() - this->Pos : 0;
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw InputError(this->Source + ":" + std::to_string(this->LineNo) + ": " + what);
  }

  /// Columns [col, col + width) of the current line (clipped).
  std::string_view Field(std::size_t col, std::size_t width) const
  {
    return col >= this->Cur.size() ? std::string_view() : this->Cur.substr(col, width);
  }

  /// Key of a data line: the integer in columns 1-2 (" -1", " -2", " -3", ...).
  int Key() const
  {
    const std::string_view f = Trim(this->Field(0, 3));
    int v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    return (f.empty() || r.ec != std::errc() || r.ptr != f.data() + f.size()) ? 0 : v;
  }

  std::int64_t Int(std::size_t col, std::size_t width, const char* what) const
  {
    const std::string_view f = Trim(this->Field(col, width));
    std::int64_t v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || r.ec != std::errc() || r.ptr != f.data() + f.size())
    {
      this->Fail(std::string("expected ") + what + " (an integer in columns " +
                 std::to_string(col + 1) + "-" + std::to_string(col + width) + "), got '" +
                 Printable(f) + "'");
    }
    return v;
  }

  double Real(std::size_t col, const char* what) const
  {
    std::string_view f = Trim(this->Field(col, 12));
    if (!f.empty() && f[0] == '+')
    {
      f.remove_prefix(1);
    }
    double v = 0;
    const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || r.ec != std::errc() || r.ptr != f.data() + f.size())
    {
      this->Fail(std::string("expected ") + what + " (an E12.5 number in columns " +
                 std::to_string(col + 1) + "-" + std::to_string(col + 12) + "), got '" +
                 Printable(f) + "'");
    }
    if (!std::isfinite(v))
    {
      this->Fail(std::string("expected ") + what + " (a finite number), got '" + Printable(f) +
                 "'");
    }
    return v;
  }

  /// Block header count, bounded by what the rest of the file can hold.
  std::size_t Count(std::size_t col,
                    std::size_t width,
                    const char* what,
                    std::size_t minBytesEach) const
  {
    const std::int64_t n = this->Int(col, width, what);
    if (n < 0 || n > std::numeric_limits<std::int32_t>::max())
    {
      this->Fail(std::string(what) + " out of range: " + std::to_string(n));
    }
    if (static_cast<std::size_t>(n) > this->BytesLeft() / minBytesEach + 1)
    {
      this->Fail(std::string(what) + " is " + std::to_string(n) +
                 " but the file is too short to hold them (truncated?)");
    }
    return static_cast<std::size_t>(n);
  }

  /// Format flag of a block header: 0 short, 1 long, 2 binary (rejected).
  int Format(std::size_t col) const
  {
    const std::string_view f = Trim(this->Field(col, 64));
    if (f.empty())
    {
      return 1; // CalculiX always writes it; long is its default
    }
    const std::int64_t v = this->Int(col, 64, "the block format (0 short, 1 long)");
    if (v == 2)
    {
      this->Fail("binary frd blocks are not supported; write the results with *NODE FILE in ASCII "
                 "(the default) instead of OUTPUT=2D/binary");
    }
    if (v != 0 && v != 1)
    {
      this->Fail("block format must be 0 (short) or 1 (long), got " + std::to_string(v));
    }
    return static_cast<int>(v);
  }

  std::string_view Cur;
  std::size_t LineNo = 0;

private:
  const std::string& Text;
  const std::string& Source;
  std::size_t Pos = 0;
};

/// Dense or hashed map from frd node ids to 0-based indices.
class NodeIndex
{
public:
  void Build(const std::vector<std::int32_t>& ids)
  {
    const std::int64_t maxId = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end());
    this->Dense = maxId <= 4 * static_cast<std::int64_t>(ids.size()) + 1024;
    if (this->Dense)
    {
      this->Table.assign(static_cast<std::size_t>(maxId) + 1, -1);
    }
    else
    {
      this->Map.reserve(ids.size());
    }
  }
  /// Returns false if the id already exists.
  bool Insert(std::int32_t id, std::int32_t index)
  {
    if (this->Dense)
    {
      if (this->Table[id] >= 0)
      {
        return false;
      }
      this->Table[id] = index;
      return true;
    }
    return this->Map.emplace(id, index).second;
  }
  std::int32_t Find(std::int64_t id) const
  {
    if (this->Dense)
    {
      return id >= 0 && id < static_cast<std::int64_t>(this->Table.size()) ? this->Table[id] : -1;
    }
    const auto it = id >= std::numeric_limits<std::int32_t>::min() &&
        id <= std::numeric_limits<std::int32_t>::max()
      ? this->Map.find(static_cast<std::int32_t>(id))
      : this->Map.end();
    return it == this->Map.end() ? -1 : it->second;
  }

private:
  bool Dense = true;
  std::vector<std::int32_t> Table;
  std::unordered_map<std::int32_t, std::int32_t> Map;
};

struct Component
{
  std::string Name;
  int Type = 0, Ind1 = 0, Ind2 = 0, Exist = 0;
};

int TensorSlot(int i, int j)
{
  if (i > j)
  {
    std::swap(i, j);
  }
  if (i == j)
  {
    return i >= 1 && i <= 3 ? i - 1 : -1;
  }
  if (i == 1 && j == 2)
  {
    return 3;
  }
  if (i == 2 && j == 3)
  {
    return 4;
  }
  if (i == 1 && j == 3)
  {
    return 5;
  }
  return -1;
}

void ReadNodes(Lines& in, FrdData& d, NodeIndex& index)
{
  const std::size_t headerLine = in.LineNo;
  const std::size_t n = in.Count(24, 12, "the number of nodes", 40);
  const int format = in.Format(36);
  const std::size_t idW = format == 1 ? 10 : 5;
  std::vector<std::int32_t> ids;
  ids.reserve(n);
  d.Points.reserve(3 * n);
  while (true)
  {
    if (!in.Next())
    {
      in.Fail("node block of line " + std::to_string(headerLine) +
              " is not terminated by ' -3' (truncated?)");
    }
    const int key = in.Key();
    if (key == -3)
    {
      break;
    }
    if (key != -1)
    {
      in.Fail("expected a node line ' -1' or the block end ' -3', got '" + Printable(in.Cur) + "'");
    }
    const std::int64_t id = in.Int(3, idW, "a node id");
    if (id < 0 || id > std::numeric_limits<std::int32_t>::max())
    {
      in.Fail("node id out of range: " + std::to_string(id));
    }
    ids.push_back(static_cast<std::int32_t>(id));
    for (int k = 0; k < 3; ++k)
    {
      d.Points.push_back(in.Real(3 + idW + 12 * k, "a node coordinate"));
    }
  }
  index.Build(ids);
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (!index.Insert(ids[i], static_cast<std::int32_t>(i)))
    {
      throw InputError("node block of line " + std::to_string(headerLine) + ": node id " +
                       std::to_string(ids[i]) + " appears twice");
    }
  }
  d.NodeIds = std::move(ids);
}

void ReadElements(Lines& in, FrdData& d, const NodeIndex& index)
{
  const std::size_t headerLine = in.LineNo;
  const std::size_t n = in.Count(24, 12, "the number of elements", 40);
  const int format = in.Format(36);
  const std::size_t idW = format == 1 ? 10 : 5;
  const std::size_t nodeW = format == 1 ? 10 : 5, perLine = format == 1 ? 10 : 15;
  d.ElementIds.reserve(n);
  d.Offsets.reserve(n + 1);
  d.Offsets.assign(1, 0);
  d.IsCornerNode.assign(d.NumNodes(), 0);
  bool more = in.Next();
  while (true)
  {
    if (!more)
    {
      in.Fail("element block of line " + std::to_string(headerLine) +
              " is not terminated by ' -3' (truncated?)");
    }
    const int key = in.Key();
    if (key == -3)
    {
      break;
    }
    if (key != -1)
    {
      in.Fail("expected an element line ' -1' or the block end ' -3', got '" + Printable(in.Cur) +
              "'");
    }
    const std::int64_t id = in.Int(3, idW, "an element id");
    const std::int64_t type = in.Int(3 + idW, 5, "an element type");
    const std::int64_t group = in.Int(8 + idW, 5, "an element group");
    const std::int64_t mat = in.Int(13 + idW, 5, "an element material");
    const int nn = FrdNodesPerElement(static_cast<int>(std::clamp<std::int64_t>(type, 0, 100)));
    if (nn == 0)
    {
      in.Fail("unknown element type " + std::to_string(type) + " (expected 1..12)");
    }
    auto clamp32 = [](std::int64_t v)
    {
      return static_cast<std::int32_t>(std::clamp<std::int64_t>(
        v, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()));
    };
    d.ElementIds.push_back(clamp32(id));
    d.ElementTypes.push_back(static_cast<std::int32_t>(type));
    d.ElementGroups.push_back(clamp32(group));
    d.ElementMaterials.push_back(clamp32(mat));
    const int corners = FrdCornersPerElement(static_cast<int>(type));
    int got = 0;
    while (got < nn)
    {
      if (!in.Next() || in.Key() != -2)
      {
        in.Fail("element " + std::to_string(id) + " (type " + std::to_string(type) + ") needs " +
                std::to_string(nn) + " node ids on ' -2' lines, got " + std::to_string(got));
      }
      for (std::size_t k = 0; k < perLine && got < nn; ++k)
      {
        const std::size_t col = 3 + nodeW * k;
        if (Trim(in.Field(col, nodeW)).empty())
        {
          break; // rest of the ids is on the next -2 line
        }
        const std::int64_t nid = in.Int(col, nodeW, "a node id of an element");
        const std::int32_t idx = index.Find(nid);
        if (idx < 0)
        {
          in.Fail("element " + std::to_string(id) + " uses node " + std::to_string(nid) +
                  " which is not in the node block");
        }
        d.Connectivity.push_back(idx);
        if (got < corners)
        {
          d.IsCornerNode[idx] = 1;
        }
        ++got;
      }
    }
    d.Offsets.push_back(static_cast<std::int64_t>(d.Connectivity.size()));
    more = in.Next();
  }
}

/// The result's name line (-4) and its component lines (-5).
std::vector<Component> ReadComponents(Lines& in, FrdResult& r)
{
  // -4 NAME NCOMPS, then NCOMPS -5 component lines
  if (!in.Next() || in.Key() != -4)
  {
    in.Fail("expected the result name line ' -4  NAME  NCOMPS' after the 100C header");
  }
  r.Name = std::string(Trim(in.Field(5, 8)));
  if (r.Name.empty())
  {
    in.Fail("empty result name");
  }
  const std::int64_t ncomps = in.Int(13, 5, "the number of components");
  if (ncomps < 1 || ncomps > 64)
  {
    in.Fail("number of components must be 1..64, got " + std::to_string(ncomps));
  }
  std::vector<Component> comps;
  for (std::int64_t c = 0; c < ncomps; ++c)
  {
    if (!in.Next() || in.Key() != -5)
    {
      in.Fail("expected component line ' -5' " + std::to_string(c + 1) + " of " +
              std::to_string(ncomps) + " of " + r.Name);
    }
    Component comp;
    comp.Name = std::string(Trim(in.Field(5, 8)));
    comp.Type = static_cast<int>(in.Int(18, 5, "the component type"));
    comp.Ind1 =
      Trim(in.Field(23, 5)).empty() ? 0 : static_cast<int>(in.Int(23, 5, "a component index"));
    comp.Ind2 =
      Trim(in.Field(28, 5)).empty() ? 0 : static_cast<int>(in.Int(28, 5, "a component index"));
    comp.Exist =
      Trim(in.Field(33, 5)).empty() ? 0 : static_cast<int>(in.Int(33, 5, "the IEXIST flag"));
    comps.push_back(comp);
  }
  return comps;
}

/// Which components the file stores (IEXIST 1 = computed by the viewer, e.g. ALL) and where
/// each goes: symmetric tensors in VTK order XX YY ZZ XY YZ XZ, vectors by index. Returns the
/// destination slot of each stored component and sets r's names, kind and size.
std::vector<int> ComponentLayout(Lines& in, const std::vector<Component>& comps, FrdResult& r)
{
  std::vector<Component> stored;
  for (const Component& c : comps)
  {
    if (c.Exist != 1)
    {
      stored.push_back(c);
    }
  }
  const int nv = static_cast<int>(stored.size());
  if (nv == 0)
  {
    in.Fail("result " + r.Name + " stores no component");
  }
  // destination slot of each stored component
  std::vector<int> slot(nv);
  for (int c = 0; c < nv; ++c)
  {
    slot[c] = c;
  }
  bool tensor = nv == 6, vector = nv == 3;
  std::vector<int> seen(6, 0);
  for (int c = 0; c < nv; ++c)
  {
    const int s = TensorSlot(stored[c].Ind1, stored[c].Ind2);
    tensor = tensor && stored[c].Type == 4 && s >= 0 && !seen[s]++;
    vector = vector && stored[c].Type == 2 && stored[c].Ind1 >= 1 && stored[c].Ind1 <= 3;
  }
  if (tensor)
  {
    static const char* names[6] = { "XX", "YY", "ZZ", "XY", "YZ", "XZ" };
    r.ComponentNames.assign(names, names + 6);
    for (int c = 0; c < nv; ++c)
    {
      slot[c] = TensorSlot(stored[c].Ind1, stored[c].Ind2);
    }
  }
  else if (vector && stored[0].Ind1 != stored[1].Ind1 && stored[0].Ind1 != stored[2].Ind1 &&
           stored[1].Ind1 != stored[2].Ind1)
  {
    r.ComponentNames.resize(3);
    for (int c = 0; c < nv; ++c)
    {
      slot[c] = stored[c].Ind1 - 1;
      r.ComponentNames[slot[c]] = stored[c].Name;
    }
  }
  else
  {
    vector = false;
    for (const Component& c : stored)
    {
      r.ComponentNames.push_back(c.Name);
    }
  }
  r.IsSymmetricTensor = tensor;
  r.IsVector = vector;
  r.NumComponents = nv;
  return slot;
}

/// The -1 / -2 value lines of a result block up to its -3 end.
void ReadResultValues(Lines& in, const NodeIndex& index, std::size_t idW,
  const std::vector<int>& slot, FrdResult& r)
{
  const int nv = r.NumComponents;
  std::vector<double> buf(nv);
  bool more = in.Next();
  while (true)
  {
    if (!more)
    {
      in.Fail("result block " + r.Name + " of line " + std::to_string(r.Line) +
              " is not terminated by ' -3' (truncated?)");
    }
    const int key = in.Key();
    if (key == -3)
    {
      break;
    }
    if (key != -1)
    {
      in.Fail("expected a value line ' -1' or the block end ' -3' in " + r.Name + ", got '" +
              Printable(in.Cur) + "'");
    }
    const std::int64_t nid = in.Int(3, idW, "a node id");
    const std::int32_t idx = index.Find(nid);
    if (idx < 0)
    {
      in.Fail("result " + r.Name + " refers to node " + std::to_string(nid) +
              " which is not in the node block");
    }
    int got = 0;
    while (true)
    {
      for (int k = 0; k < 6 && got < nv; ++k, ++got)
      {
        buf[got] = in.Real(3 + idW + 12 * k, "a result value");
      }
      if (got == nv)
      {
        break;
      }
      if (!in.Next() || in.Key() != -2)
      {
        in.Fail("node " + std::to_string(nid) + " of " + r.Name + " needs " + std::to_string(nv) +
                " values; expected a continuation line ' -2'");
      }
    }
    double* out = r.Values.data() + static_cast<std::size_t>(idx) * nv;
    for (int c = 0; c < nv; ++c)
    {
      out[slot[c]] = buf[c];
    }
    more = in.Next();
  }
}

void ReadResult(Lines& in, FrdData& d, const NodeIndex& index)
{
  FrdResult r;
  r.Line = in.LineNo;
  r.Value = in.Real(12, "the step value (time/frequency)");
  in.Int(24, 12, "the number of nodes of the result block"); // checked, not needed
  r.Step = static_cast<int>(std::clamp<std::int64_t>(in.Int(58, 5, "the step number (NUMSTP)"),
                                                     std::numeric_limits<int>::min(),
                                                     std::numeric_limits<int>::max()));
  r.Analysis = std::string(Trim(in.Field(63, 10)));
  const int format = in.Format(73);
  const std::size_t idW = format == 1 ? 10 : 5;

  const std::vector<Component> comps = ReadComponents(in, r);
  const std::vector<int> slot = ComponentLayout(in, comps, r);
  r.Values.assign(d.NumNodes() * static_cast<std::size_t>(r.NumComponents), 0.0);
  ReadResultValues(in, index, idW, slot, r);
  d.Results.push_back(std::move(r));
}

} // namespace

FrdData ParseFrd(const std::string& text, const std::string& sourceName)
{
  FrdData d;
  NodeIndex index;
  bool haveNodes = false, haveElements = false;
  Lines in(text, sourceName);
  while (in.Next())
  {
    const std::string_view head = in.Field(0, 6);
    const std::string_view key = Trim(in.Field(0, 5));
    const bool isC = head.size() == 6 && head[5] == 'C';
    if (isC && key == "2")
    {
      if (haveNodes)
      {
        in.Fail("a second node block");
      }
      ReadNodes(in, d, index);
      haveNodes = true;
    }
    else if (isC && key == "3")
    {
      if (!haveNodes)
      {
        in.Fail("element block before the node block");
      }
      if (haveElements)
      {
        in.Fail("a second element block");
      }
      ReadElements(in, d, index);
      haveElements = true;
    }
    else if (isC && key == "100")
    {
      if (!haveNodes)
      {
        in.Fail("result block before the node block");
      }
      ReadResult(in, d, index);
    }
    else if (key == "9999")
    {
      break;
    }
    // everything else (1C, 1U, 1P parameter lines, blank lines) carries no geometry
  }
  if (!haveNodes)
  {
    throw InputError(sourceName + ": no node block ('    2C'): not a CalculiX .frd file?");
  }
  if (!haveElements)
  {
    d.Offsets.assign(1, 0);
    d.IsCornerNode.assign(d.NumNodes(), 0);
  }
  return d;
}

FrdData ReadFrd(const std::string& fileName)
{
  return ParseFrd(ReadFileBytes(fileName), fileName);
}

} // namespace av
