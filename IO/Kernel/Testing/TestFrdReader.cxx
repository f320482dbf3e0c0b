// SPDX-License-Identifier: BSD-3-Clause
// Tests the CalculiX .frd reader on a hand-made file of two 20-node hexahedra (fixed columns,
// glued numbers, node order, tensor/vector component order, several steps), its errors, a
// fuzz loop, and, when the Debian package calculix-cgx-examples is installed, the real
// compressor example result.frd (read at run time, never copied into the repository).
#include "AnisoTestChecks.h"
#include "FrdReader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace
{

std::string Fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string Fmt(const char* f, ...)
{
  char buf[512];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof(buf), f, ap);
  va_end(ap);
  return buf;
}

// Reference hex corners in VTK/CalculiX-input order and the 12 edges of VTK's
// quadratic hexahedron (mid-edge nodes 8..19).
const double Corner[8][3] = { { 0, 0, 0 },
  { 1, 0, 0 },
  { 1, 1, 0 },
  { 0, 1, 0 },
  { 0, 0, 1 },
  { 1, 0, 1 },
  { 1, 1, 1 },
  { 0, 1, 1 } };
const int VTKEdges[12][2] = { { 0, 1 },
  { 1, 2 },
  { 2, 3 },
  { 3, 0 },
  { 4, 5 },
  { 5, 6 },
  { 6, 7 },
  { 7, 4 },
  { 0, 4 },
  { 1, 5 },
  { 2, 6 },
  { 3, 7 } };
// frd writes bottom edges, then vertical edges, then top edges.
const int FrdEdgeOrder[12] = { 0, 1, 2, 3, 8, 9, 10, 11, 4, 5, 6, 7 };

struct Hand
{
  std::string Text;
  std::vector<std::array<double, 3>> Pts; // by node id - 1
};

/// Two he20 hexes side by side along x, shifted to negative coordinates so that the E12.5
/// fields are glued ("-1.00000E+00-2.00000E+00"). Node ids are not contiguous (id = 10*i+5).
/// Frd id of hand-made node i.
int HandNodeId(int i)
{
  return 10 * i + 5;
}

/// Two he20 elements side by side: the shared nodes once, corners then mid-edge nodes in FRD
/// order; fills h.Pts and returns the elements' node indices.
std::vector<std::array<int, 20>> MakeHandElements(Hand& h)
{
  std::vector<std::array<int, 20>> elems(2);
  auto addNode = [&](double x, double y, double z)
  {
    for (std::size_t i = 0; i < h.Pts.size(); ++i)
    {
      if (std::abs(h.Pts[i][0] - x) + std::abs(h.Pts[i][1] - y) + std::abs(h.Pts[i][2] - z) < 1e-12)
      {
        return static_cast<int>(i);
      }
    }
    h.Pts.push_back({ x, y, z });
    return static_cast<int>(h.Pts.size() - 1);
  };
  for (int e = 0; e < 2; ++e)
  {
    for (int c = 0; c < 8; ++c)
    {
      elems[e][c] = addNode(Corner[c][0] + e - 2.0, Corner[c][1] - 3.0, Corner[c][2] - 1.5);
    }
    for (int k = 0; k < 12; ++k)
    {
      const int* ed = VTKEdges[FrdEdgeOrder[k]];
      elems[e][8 + k] = addNode(0.5 * (Corner[ed[0]][0] + Corner[ed[1]][0]) + e - 2.0,
        0.5 * (Corner[ed[0]][1] + Corner[ed[1]][1]) - 3.0,
        0.5 * (Corner[ed[0]][2] + Corner[ed[1]][2]) - 1.5);
    }
  }
  return elems;
}

/// The node (2C) and element (3C) blocks.
void AppendMeshBlocks(std::string& s,
  const Hand& h,
  const std::vector<std::array<int, 20>>& elems,
  bool shortFormat)
{
  const int np = static_cast<int>(h.Pts.size());
  auto id = HandNodeId;
  s += "    1C\n    1UUSER  hand-made test file\n";
  s += Fmt("    2C%18s%12d%37s%1d\n", "", np, "", shortFormat ? 0 : 1);
  for (int i = 0; i < np; ++i)
  {
    s += shortFormat
      ? Fmt(" -1%5d%12.5E%12.5E%12.5E\n", id(i), h.Pts[i][0], h.Pts[i][1], h.Pts[i][2])
      : Fmt(" -1%10d%12.5E%12.5E%12.5E\n", id(i), h.Pts[i][0], h.Pts[i][1], h.Pts[i][2]);
  }
  s += " -3\n";
  s += Fmt("    3C%18s%12d%37s%1d\n", "", 2, "", shortFormat ? 0 : 1);
  for (int e = 0; e < 2; ++e)
  {
    if (shortFormat)
    {
      s += Fmt(" -1%5d%5d%5d%5d\n -2", 100 + e, 4, 0, 7);
      for (int k = 0; k < 20; ++k)
      {
        s += Fmt("%5d", id(elems[e][k]));
        if (k == 14)
        {
          s += "\n -2";
        }
      }
    }
    else
    {
      s += Fmt(" -1%10d%5d%5d%5d\n -2", 100 + e, 4, 0, 7);
      for (int k = 0; k < 20; ++k)
      {
        s += Fmt("%10d", id(elems[e][k]));
        if (k == 9)
        {
          s += "\n -2";
        }
      }
    }
    s += "\n";
  }
  s += " -3\n";
}

/// Two steps of DISP and STRESS, a tensor with its components out of order, a 7-component
/// block with a continuation line, and the end.
void AppendResultBlocks(std::string& s, const Hand& h, bool shortFormat)
{
  const int np = static_cast<int>(h.Pts.size());
  auto id = HandNodeId;
  const char* fmtId = shortFormat ? " -1%5d" : " -1%10d";
  for (int step = 1; step <= 2; ++step)
  {
    s += "    1PSTEP                         1           1           1\n";
    s += Fmt("  100CL  10%d%12.5E%12d%20s%2d%5d%-10s%2d\n",
      step,
      1000.0 * step,
      np,
      "",
      2,
      step,
      "MODAL",
      shortFormat ? 0 : 1);
    s += " -4  DISP        4    1\n";
    s += " -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n";
    s += " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n";
    for (int i = 0; i < np; ++i)
    {
      s += Fmt(fmtId, id(i)) +
        Fmt("%12.5E%12.5E%12.5E\n", -h.Pts[i][0] * step, -1.0 * step, -2.0 * step);
    }
    s += " -3\n";
    s += Fmt("  100CL  10%d%12.5E%12d%20s%2d%5d%-10s%2d\n",
      step,
      1000.0 * step,
      np,
      "",
      2,
      step,
      "MODAL",
      shortFormat ? 0 : 1);
    s += " -4  STRESS      6    1\n";
    s += " -5  SXX         1    4    1    1\n -5  SYY         1    4    2    2\n";
    s += " -5  SZZ         1    4    3    3\n -5  SXY         1    4    1    2\n";
    s += " -5  SYZ         1    4    2    3\n -5  SZX         1    4    3    1\n";
    for (int i = 0; i < np; ++i)
    { // values 11..16 (+ node/step offsets): all distinct
      const double b = 100.0 * i + 1000.0 * step;
      s += Fmt(fmtId, id(i)) +
        Fmt("%12.5E%12.5E%12.5E%12.5E%12.5E%12.5E\n",
          -(b + 11),
          b + 12,
          b + 13,
          b + 14,
          b + 15,
          b + 16);
    }
    s += " -3\n";
  }
  // a tensor block whose components come in a non-standard order (EZX before EYZ)
  s += Fmt(
    "  100CL  109%12.5E%12d%20s%2d%5d%-10s%2d\n", 0.0, np, "", 2, 9, "STATIC", shortFormat ? 0 : 1);
  s += " -4  TOSTRAIN    6    1\n";
  s += " -5  EXX         1    4    1    1\n -5  EYY         1    4    2    2\n";
  s += " -5  EZZ         1    4    3    3\n -5  EXY         1    4    1    2\n";
  s += " -5  EZX         1    4    3    1\n -5  EYZ         1    4    2    3\n";
  s +=
    Fmt(fmtId, id(0)) + Fmt("%12.5E%12.5E%12.5E%12.5E%12.5E%12.5E\n", 1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
  s += " -3\n";
  // a 7-component block: the 7th value is on a ' -2' continuation line
  s += Fmt(
    "  100CL  109%12.5E%12d%20s%2d%5d%-10s%2d\n", 0.0, np, "", 2, 9, "STATIC", shortFormat ? 0 : 1);
  s += " -4  SEVEN       7    1\n";
  for (int c = 1; c <= 7; ++c)
  {
    s += Fmt(" -5  C%-7d     1    1    0    0\n", c);
  }
  s +=
    Fmt(fmtId, id(1)) + Fmt("%12.5E%12.5E%12.5E%12.5E%12.5E%12.5E\n", 1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
  s += Fmt(shortFormat ? " -2%5s" : " -2%10s", "") + Fmt("%12.5E\n", 7.0);
  s += " -3\n 9999\n";
}

Hand MakeFrd(bool shortFormat = false)
{
  Hand h;
  const std::vector<std::array<int, 20>> elems = MakeHandElements(h);
  AppendMeshBlocks(h.Text, h, elems, shortFormat);
  AppendResultBlocks(h.Text, h, shortFormat);
  return h;
}

bool IsMidpoint(const double* m, const double* a, const double* b, double tol)
{
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(m[k] - 0.5 * (a[k] + b[k])) > tol)
    {
      return false;
    }
  }
  return true;
}

/// Every mid-edge node, in VTK order, is the midpoint of VTK's edge corners.
int CountWrongMidEdges(const av::FrdData& d, double relTol)
{
  int wrong = 0;
  for (std::size_t e = 0; e < d.NumElements(); ++e)
  {
    if (d.ElementTypes[e] != av::FrdHe20)
    {
      continue;
    }
    const int* order = av::FrdToVTKNodeOrder(av::FrdHe20);
    const std::int32_t* conn = d.Connectivity.data() + d.Offsets[e];
    auto P = [&](int vtkNode) { return d.Points.data() + 3 * conn[order[vtkNode]]; };
    for (int k = 0; k < 12; ++k)
    {
      const double* a = P(VTKEdges[k][0]);
      const double* b = P(VTKEdges[k][1]);
      const double len = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
        (a[2] - b[2]) * (a[2] - b[2]));
      wrong += IsMidpoint(P(8 + k), a, b, relTol * len) ? 0 : 1;
    }
  }
  return wrong;
}

/// Wedges: a CalculiX-ordered pe15 (base counterclockwise seen from the top, mid-edges
/// bottom / vertical / top) must become a VTK wedge whose (0,1,2) normal points away from
/// (3,4,5) and whose mid-edge nodes lie on VTK's edges.
void TestWedgeOrder()
{
  const double c[6][3] = {
    { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }
  };
  const int frdEdges[9][2] = {
    { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 4 }, { 2, 5 }, { 3, 4 }, { 4, 5 }, { 5, 3 }
  };
  const int vtkEdges[9][2] = {
    { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 }
  };
  double frd[15][3];
  for (int i = 0; i < 6; ++i)
  {
    std::copy(c[i], c[i] + 3, frd[i]);
  }
  for (int e = 0; e < 9; ++e)
  {
    for (int k = 0; k < 3; ++k)
    {
      frd[6 + e][k] = 0.5 * (c[frdEdges[e][0]][k] + c[frdEdges[e][1]][k]);
    }
  }
  for (int type : { av::FrdPe6, av::FrdPe15 })
  {
    const int* order = av::FrdToVTKNodeOrder(type);
    auto P = [&](int i) { return frd[order[i]]; };
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = P(1)[k] - P(0)[k];
      v[k] = P(2)[k] - P(0)[k];
      w[k] = (P(3)[k] + P(4)[k] + P(5)[k] - P(0)[k] - P(1)[k] - P(2)[k]) / 3.0;
    }
    const double n[3] = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
    };
    AV_CHECK_MSG(
      n[0] * w[0] + n[1] * w[1] + n[2] * w[2] < 0, "wedge type " << type << " base normal");
    if (type == av::FrdPe15)
    {
      for (int e = 0; e < 9; ++e)
      {
        AV_CHECK_MSG(
          IsMidpoint(P(6 + e), P(vtkEdges[e][0]), P(vtkEdges[e][1]), 1e-12), "pe15 edge " << e);
      }
    }
  }
}

void TestHandMade(bool shortFormat)
{
  const Hand h = MakeFrd(shortFormat);
  const av::FrdData d = av::ParseFrd(h.Text, "hand.frd");
  AV_CHECK(d.NumNodes() == h.Pts.size() && d.NumNodes() == 32);
  AV_CHECK(d.NodeIds[3] == 35);
  for (std::size_t i = 0; i < d.NumNodes(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      AV_CHECK_NEAR(d.Points[3 * i + k], h.Pts[i][k], 1e-12); // glued fields split by column
    }
  }
  AV_CHECK(d.NumElements() == 2 && d.ElementIds[1] == 101 && d.ElementTypes[0] == 4);
  AV_CHECK(d.ElementMaterials[1] == 7 && d.Offsets.size() == 3 && d.Offsets[2] == 40);
  int corners = 0;
  for (std::uint8_t c : d.IsCornerNode)
  {
    corners += c;
  }
  AV_CHECK(corners == 12); // two hexes sharing a face
  AV_CHECK(CountWrongMidEdges(d, 1e-9) == 0);

  AV_CHECK(d.Results.size() == 6);
  AV_CHECK(d.Steps() == std::vector<int>({ 1, 2, 9 }));
  const int disp2 = d.FindResult("DISP", 2);
  AV_CHECK(disp2 >= 0);
  if (disp2 >= 0)
  {
    const av::FrdResult& r = d.Results[disp2];
    AV_CHECK(r.IsVector && r.NumComponents == 3 && r.Value == 2000.0 && r.Analysis == "MODAL");
    AV_CHECK(r.ComponentNames.size() == 3 && r.ComponentNames[2] == "D3");
    AV_CHECK_NEAR(r.Values[3 * 5 + 0], -2.0 * h.Pts[5][0], 1e-9);
    AV_CHECK(r.Values[3 * 5 + 2] == -4.0);
  }
  const int st1 = d.FindResult("STRESS", 1);
  AV_CHECK(st1 >= 0);
  if (st1 >= 0)
  {
    const av::FrdResult& r = d.Results[st1];
    AV_CHECK(r.IsSymmetricTensor && r.NumComponents == 6 && r.ComponentNames[5] == "XZ");
    const double b = 100.0 * 7 + 1000.0;
    const double expect[6] = { -(b + 11), b + 12, b + 13, b + 14, b + 15, b + 16 };
    for (int c = 0; c < 6; ++c)
    {
      AV_CHECK_NEAR(r.Values[6 * 7 + c], expect[c], 1e-6 * b);
    }
  }
  const int eps = d.FindResult("TOSTRAIN", 9);
  AV_CHECK(eps >= 0);
  if (eps >= 0)
  { // file order XX YY ZZ XY ZX YZ = 1..6 -> VTK XX YY ZZ XY YZ XZ
    const av::FrdResult& r = d.Results[eps];
    const double expect[6] = { 1, 2, 3, 4, 6, 5 };
    for (int c = 0; c < 6; ++c)
    {
      AV_CHECK(r.Values[c] == expect[c]);
    }
    AV_CHECK(r.Values[6] == 0.0); // node absent from the block
  }
  const int seven = d.FindResult("SEVEN", 9);
  AV_CHECK(
    seven >= 0 && d.Results[seven].NumComponents == 7 && d.Results[seven].Values[7 + 6] == 7.0);
}

std::string MessageOf(const std::string& text)
{
  try
  {
    av::ParseFrd(text, "f");
  }
  catch (const av::InputError& e)
  {
    return e.what();
  }
  return "";
}

std::string Replace(std::string s, const std::string& from, const std::string& to)
{
  const std::size_t p = s.find(from);
  if (p != std::string::npos)
  {
    s.replace(p, from.size(), to);
  }
  return s;
}

void TestErrors()
{
  const std::string good = MakeFrd().Text;
  // node id 15 is on line 5 (after 1C, 1U, 2C and node 5)
  std::string msg = MessageOf(Replace(good, " -1        15", " -1        1x"));
  AV_CHECK_MSG(msg.find("f:5:") == 0 && msg.find("node id") != std::string::npos, msg);
  msg = MessageOf(Replace(good, "-3.00000E+00", "         nan"));
  AV_CHECK_MSG(msg.find("f:4:") == 0 && msg.find("finite") != std::string::npos, msg);
  msg = MessageOf(Replace(good, "  100    4", "  100   44"));
  AV_CHECK_MSG(msg.find("unknown element type 44") != std::string::npos, msg);
  msg = MessageOf(Replace(good, "        25        35", "        25     99999"));
  AV_CHECK_MSG(msg.find("node 99999") != std::string::npos, msg);
  msg = MessageOf(good.substr(0, good.find(" -3")));
  AV_CHECK_MSG(msg.find("not terminated") != std::string::npos, msg);
  msg = MessageOf(good.substr(0, good.find("SZX") + 40)); // inside a result block
  AV_CHECK_MSG(
    msg.find("not terminated") != std::string::npos || msg.find("expected") != std::string::npos,
    msg);
  const std::string nodeHeader = Fmt("    2C%18s%12d%37s%1d\n", "", 32, "", 1);
  msg = MessageOf(
    Replace(good, nodeHeader, Fmt("    2C%18s%12lld%37s%1d\n", "", 999999999999LL, "", 1)));
  AV_CHECK_MSG(msg.find("f:3:") == 0, msg);
  msg = MessageOf(Replace(good, nodeHeader, Fmt("    2C%18s%12d%37s%1d\n", "", 20000000, "", 1)));
  AV_CHECK_MSG(msg.find("f:3:") == 0 && msg.find("truncated") != std::string::npos, msg);
  msg = MessageOf(Replace(good, nodeHeader, Fmt("    2C%18s%12d%37s%1d\n", "", 32, "", 2)));
  AV_CHECK_MSG(msg.find("binary") != std::string::npos, msg);
  AV_CHECK_THROWS(av::ParseFrd("    1C\n 9999\n"));
  AV_CHECK_THROWS(av::ParseFrd(Replace(good, " -4  DISP        4", " -4  DISP        0")));
  AV_CHECK_THROWS(av::ReadFrd("/nonexistent/x.frd"));
}

void TestFuzz()
{
  const std::string valid = MakeFrd().Text;
  std::mt19937 rng(99);
  const char bytes[] = "0123456789-+.E \n";
  int parsed = 0, rejected = 0;
  for (int it = 0; it < 3000; ++it)
  {
    std::string s = valid;
    const int mode = static_cast<int>(rng() % 3);
    if (mode != 1)
    {
      s.resize(rng() % (s.size() + 1));
    }
    if (mode != 0)
    {
      for (int k = 0; k < 1 + static_cast<int>(rng() % 4) && !s.empty(); ++k)
      {
        s[rng() % s.size()] = bytes[rng() % (sizeof(bytes) - 1)];
      }
    }
    try
    {
      const av::FrdData d = av::ParseFrd(s);
      AV_CHECK(d.Offsets.size() == d.NumElements() + 1 && d.Points.size() == 3 * d.NumNodes());
      for (std::int32_t c : d.Connectivity)
      {
        AV_CHECK(c >= 0 && static_cast<std::size_t>(c) < d.NumNodes());
      }
      for (const av::FrdResult& r : d.Results)
      {
        AV_CHECK(r.Values.size() == d.NumNodes() * r.NumComponents);
      }
      ++parsed;
    }
    catch (const av::InputError&)
    {
      ++rejected;
    }
    catch (const std::exception& e)
    {
      AV_CHECK_MSG(false, "unexpected exception " << e.what());
    }
  }
  AV_CHECK(parsed > 0 && rejected > 0);
  std::cout << "fuzz: " << parsed << " parsed, " << rejected << " rejected\n";
}

void TestCalculixExample()
{
  const char* path = "/usr/share/doc/calculix-cgx-examples/examples/result.frd";
  if (!std::ifstream(path))
  {
    std::cout << "skipping the CalculiX example: " << path
              << " not found (apt-get install calculix-cgx-examples)\n";
    return;
  }
  const av::FrdData d = av::ReadFrd(path);
  AV_CHECK(d.NumNodes() == 3150 && d.NumElements() == 560);
  bool allHe20 = true;
  for (std::int32_t t : d.ElementTypes)
  {
    allHe20 = allHe20 && t == av::FrdHe20;
  }
  AV_CHECK(allHe20);
  // mid-edge nodes of the curved impeller are near, not exactly at, edge midpoints
  AV_CHECK(CountWrongMidEdges(d, 0.05) == 0);
  AV_CHECK(d.Results.size() == 20);
  AV_CHECK(d.Steps().size() == 10);
  const int s1 = d.FindResult("STRESS", 1);
  AV_CHECK(s1 >= 0);
  if (s1 >= 0)
  { // node 1: SXX SYY SZZ SXY SYZ SZX = -2.58632E+03 -1.28513E+06
    // -2.91480E+05 1.59342E+04 6.09583E+05 -7.57145E+03
    const double* v = d.Results[s1].Values.data();
    AV_CHECK(v[0] == -2.58632E+03 && v[1] == -1.28513E+06 && v[2] == -2.91480E+05);
    AV_CHECK(v[3] == 1.59342E+04 && v[4] == 6.09583E+05 && v[5] == -7.57145E+03);
    AV_CHECK(d.Results[s1].Value == 1.04598E+04);
  }
  const int d10 = d.FindResult("DISP", 10);
  AV_CHECK(d10 >= 0 && d.Results[d10].IsVector);
}

} // namespace

int TestFrdReader(int, char*[])
{
  TestWedgeOrder();
  TestHandMade(false);
  TestHandMade(true);
  TestErrors();
  TestFuzz();
  TestCalculixExample();
  return AV_TEST_RESULT();
}
