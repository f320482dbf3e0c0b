// SPDX-License-Identifier: BSD-3-Clause
// Tests the binary Medit .meshb/.solb reader and writer: the byte layout of a small file
// (libMeshb's format description), exact ASCII <-> binary round trips of meshes and
// metrics, big-endian and version 1 (float) / 4 (int64) files, skipped unknown keywords,
// file functions picking the format, and a fuzz loop (truncations / byte flips).
#include "AnisoTestChecks.h"
#include "MeditBinaryIO.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>

namespace
{

const char* TetMesh = R"(MeshVersionFormatted 2
Dimension 3
Vertices 5
0 0 0 1
1 0 0 2
0 1 0 3
0 0 1 4
0.1 0.3333333333333333 1e-300 5
Tetrahedra 2
1 2 3 4 10
2 3 4 5 20
Triangles 1
1 2 3 7
Edges 1
1 2 9
End
)";

std::int32_t Int32At(const std::string& b, std::size_t pos)
{
  std::int32_t v;
  std::memcpy(&v, b.data() + pos, 4);
  return v;
}

/// Little-endian words as a libMeshb writer lays them out (built by hand, not by our writer).
struct Bytes
{
  std::string S;
  int Version;
  explicit Bytes(int version)
    : Version(version)
  {
    I32(1);
    I32(version);
  }
  void I32(std::int32_t v) { S.append(reinterpret_cast<const char*>(&v), 4); }
  void I64(std::int64_t v) { S.append(reinterpret_cast<const char*>(&v), 8); }
  void Int(std::int64_t v) { Version >= 4 ? I64(v) : I32(static_cast<std::int32_t>(v)); }
  void Pos(std::int64_t v) { Version >= 3 ? I64(v) : I32(static_cast<std::int32_t>(v)); }
  void Real(double v)
  {
    if (Version == 1)
    {
      const float f = static_cast<float>(v);
      S.append(reinterpret_cast<const char*>(&f), 4);
    }
    else
      S.append(reinterpret_cast<const char*>(&v), 8);
  }
};

/// A 2D mesh of one triangle with a Corners keyword (13: vertex 2) between, in `version`.
std::string HandMadeTriangle(int version)
{
  Bytes b(version);
  b.I32(3);
  b.Pos(0); // readers go on sequentially after Dimension
  b.I32(2);
  b.I32(4);
  b.Pos(0);
  b.Int(3);
  const double xy[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
  for (int i = 0; i < 3; ++i)
  {
    b.Real(xy[i][0]);
    b.Real(xy[i][1]);
    b.Int(i + 1);
  }
  b.I32(13); // Corners, with its next position
  const std::size_t patch = b.S.size();
  b.Pos(0);
  b.Int(1);
  b.Int(2);
  const std::int64_t next = static_cast<std::int64_t>(b.S.size());
  if (version >= 3)
    std::memcpy(&b.S[patch], &next, 8);
  else
  {
    const auto n32 = static_cast<std::int32_t>(next);
    std::memcpy(&b.S[patch], &n32, 4);
  }
  b.I32(6);
  b.Pos(0);
  b.Int(1);
  b.Int(1);
  b.Int(2);
  b.Int(3);
  b.Int(42);
  b.I32(54);
  b.Pos(0);
  return b.S;
}

void TestLayout()
{
  // Our writer's bytes: code 1, version 2, Dimension (3) with the next keyword's position,
  // then Vertices (4) whose position field points at Tetrahedra (8).
  const av::MeditMesh m = av::ParseMeditMesh(TetMesh);
  const std::string b = av::FormatMeditMeshBinary(m);
  AV_CHECK(av::IsMeditBinary(b));
  AV_CHECK(Int32At(b, 0) == 1 && Int32At(b, 4) == 2);
  AV_CHECK(Int32At(b, 8) == 3 && Int32At(b, 12) == 20 && Int32At(b, 16) == 3);
  AV_CHECK(Int32At(b, 20) == 4);
  const std::int32_t tetPos = Int32At(b, 24);
  AV_CHECK(Int32At(b, 28) == 5);            // 5 vertices
  AV_CHECK(tetPos == 32 + 5 * (3 * 8 + 4)); // 3 doubles + int32 ref each
  AV_CHECK(Int32At(b, static_cast<std::size_t>(tetPos)) == 8);
  AV_CHECK(Int32At(b, b.size() - 8) == 54 && Int32At(b, b.size() - 4) == 0); // End, position 0
}

void TestRoundTrips()
{
  const av::MeditMesh a = av::ParseMeditMesh(TetMesh);
  const av::MeditMesh b = av::ParseMeditMeshBinary(av::FormatMeditMeshBinary(a));
  AV_CHECK(b.Mesh.Points == a.Mesh.Points); // bit-exact doubles, including 1e-300
  AV_CHECK(b.Mesh.Cells == a.Mesh.Cells && b.CellRefs == a.CellRefs);
  AV_CHECK(b.Faces == a.Faces && b.FaceRefs == a.FaceRefs);
  AV_CHECK(b.Edges == a.Edges && b.EdgeRefs == a.EdgeRefs && b.PointRefs == a.PointRefs);
  AV_CHECK(b.Mesh.SimplexDim == 3 && b.Mesh.AmbientDim == 3);
  { // Corners and Ridges (libMeshb codes 13 and 14) both ways; out-of-range ones refused.
    av::MeditMesh f = a;
    f.Corners = { 0, 4 };
    f.Ridges = { 0 };
    const std::string bin = av::FormatMeditMeshBinary(f);
    const av::MeditMesh g = av::ParseMeditMeshBinary(bin);
    AV_CHECK(g.Corners == f.Corners && g.Ridges == f.Ridges && g.IgnoredKeywords.empty());
    AV_CHECK(av::ParseMeditMesh(av::FormatMeditMesh(g)).Ridges == f.Ridges);
    // The Ridges section (code 14, next position, count, entry 1) comes last before End.
    AV_CHECK(Int32At(bin, bin.size() - 12) == 1 && Int32At(bin, bin.size() - 24) == 14);
    std::string badRidge = bin;
    const std::int32_t two = 2;
    std::memcpy(&badRidge[bin.size() - 12], &two, 4);
    AV_CHECK_THROWS(av::ParseMeditMeshBinary(badRidge, "bad"));
  }
  // binary -> ASCII -> binary is the same bytes
  AV_CHECK(av::FormatMeditMeshBinary(av::ParseMeditMesh(av::FormatMeditMesh(b))) ==
    av::FormatMeditMeshBinary(a));

  // Metrics, 3D and 2D: VTK order in memory, Medit order in the file, both ways exact.
  for (int dim : { 2, 3 })
  {
    av::MetricField metric;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 6; ++k)
        metric.Values.push_back(dim == 2 && (k == 2 || k == 4 || k == 5) ? 0.0 : 1.0 / (i + k + 3));
    const av::MeditSol sol = av::MeditSolFromMetric(metric, dim);
    const std::string bin = av::FormatMeditSolBinary(sol);
    const av::MeditSol back = av::ParseMeditSolBinary(bin);
    AV_CHECK(back.Dimension == dim && back.NumVertices == 4 && back.FieldTypes == sol.FieldTypes);
    AV_CHECK(back.Fields == sol.Fields);
    const av::MeditSol viaAscii = av::ParseMeditSol(av::FormatMeditSol(back));
    AV_CHECK(viaAscii.Fields == sol.Fields);
    AV_CHECK(av::MetricFromMeditSol(back).Values == metric.Values);
    // The file holds Medit's lower triangle: XX, XY, YY (2D) after the 3 header words.
    const std::size_t firstValue = 8 + 12 + 8 + 4 + 4 + 4; // header, Dimension, kwd, n, ntyp, typ
    double v[3];
    std::memcpy(v, bin.data() + firstValue, sizeof v);
    AV_CHECK(v[0] == metric.Values[0] && v[1] == metric.Values[3] && v[2] == metric.Values[1]);
  }
}

void TestOtherVersions()
{
  for (int version : { 1, 2, 3, 4 })
  {
    const av::MeditMesh m = av::ParseMeditMeshBinary(HandMadeTriangle(version), "v");
    AV_CHECK_MSG(m.Mesh.SimplexDim == 2 && m.Mesh.AmbientDim == 2 && m.Mesh.NumPoints() == 3,
      "version " << version);
    AV_CHECK(m.Mesh.Cells == (std::vector<std::int32_t>{ 0, 1, 2 }) && m.CellRefs[0] == 42);
    AV_CHECK(m.PointRefs == (std::vector<std::int32_t>{ 1, 2, 3 }) && m.Mesh.Points[3] == 0.0);
    AV_CHECK(m.IgnoredKeywords.empty() && m.Corners == std::vector<std::int32_t>{ 1 });
  }
  // Big-endian: every 4- or 8-byte word reversed.
  const std::string le = HandMadeTriangle(2);
  std::string be = le;
  // version 2 words: int32 everywhere except the doubles of the Vertices lines
  std::size_t pos = 0;
  auto swap = [&](std::size_t n)
  {
    std::reverse(be.begin() + static_cast<long>(pos), be.begin() + static_cast<long>(pos + n));
    pos += n;
  };
  for (int k = 0; k < 7; ++k)
    swap(4); // code, version, Dimension kwd/pos/value, Vertices kwd/pos
  swap(4);   // count
  for (int i = 0; i < 3; ++i)
  {
    swap(8);
    swap(8);
    swap(4);
  }
  while (pos < be.size())
    swap(4);
  AV_CHECK(av::IsMeditBinary(be));
  const av::MeditMesh big = av::ParseMeditMeshBinary(be, "be");
  const av::MeditMesh little = av::ParseMeditMeshBinary(le, "le");
  AV_CHECK(big.Mesh.Points == little.Mesh.Points && big.Mesh.Cells == little.Mesh.Cells);
  AV_CHECK(big.CellRefs == little.CellRefs);
}

void TestFiles(const std::string& tmp)
{
  const av::MeditMesh m = av::ParseMeditMesh(TetMesh);
  const std::string ascii = tmp + "/medit_binary_test.mesh",
                    binary = tmp + "/medit_binary_test.meshb";
  av::WriteMeditMeshFile(ascii, m);
  av::WriteMeditMeshFile(binary, m);
  AV_CHECK(av::ReadMeditMeshFile(ascii).Mesh.Points == m.Mesh.Points);
  AV_CHECK(av::ReadMeditMeshFile(binary).Mesh.Cells == m.Mesh.Cells);
  av::MeditSol sol = av::MeditSolFromMetric(av::MetricField{ std::vector<double>(30, 0.5) }, 3);
  av::WriteMeditSolFile(tmp + "/medit_binary_test.solb", sol);
  AV_CHECK(av::ReadMeditSolFile(tmp + "/medit_binary_test.solb").Fields == sol.Fields);
  AV_CHECK_THROWS(av::ReadMeditMeshFile(tmp + "/no_such_file.meshb"));
}

void TestErrors()
{
  const std::string b = av::FormatMeditMeshBinary(av::ParseMeditMesh(TetMesh));
  std::string badId = b;
  const std::size_t firstTetId = static_cast<std::size_t>(Int32At(b, 24)) + 12;
  const std::int32_t huge = 99;
  std::memcpy(&badId[firstTetId], &huge, 4);
  try
  {
    av::ParseMeditMeshBinary(badId, "bad.meshb");
    AV_CHECK_MSG(false, "an out-of-range vertex id must be rejected");
  }
  catch (const av::InputError& e)
  {
    const std::string what = e.what();
    AV_CHECK_MSG(what.find("bad.meshb") != std::string::npos &&
        what.find("Tetrahedra 1") != std::string::npos && what.find("99") != std::string::npos,
      what);
  }
  AV_CHECK_THROWS(av::ParseMeditMeshBinary(b.substr(0, 40)));
  AV_CHECK_THROWS(av::ParseMeditMeshBinary(std::string("\1\0\0\0\7\0\0\0", 8)));
}

void TestFuzz()
{
  const std::string mesh = av::FormatMeditMeshBinary(av::ParseMeditMesh(TetMesh));
  const std::string sol = av::FormatMeditSolBinary(
    av::MeditSolFromMetric(av::MetricField{ std::vector<double>(30, 2.0) }, 3));
  std::mt19937 rng(2024);
  int parsed = 0, rejected = 0;
  for (int it = 0; it < 6000; ++it)
  {
    const bool isSol = (it % 2) == 1;
    std::string s = isSol ? sol : mesh;
    const int mode = static_cast<int>(rng() % 3);
    if (mode != 1)
      s.resize(rng() % (s.size() + 1));
    if (mode >= 1)
      for (int k = 0, flips = 1 + static_cast<int>(rng() % 4); k < flips && !s.empty(); ++k)
        s[rng() % s.size()] = static_cast<char>(rng() % 256);
    try
    {
      if (isSol)
      {
        const av::MeditSol r = av::ParseMeditSolBinary(s);
        for (std::size_t f = 0; f < r.Fields.size(); ++f)
          AV_CHECK(r.Fields[f].size() == r.NumVertices * r.FieldComponents(r.FieldTypes[f]));
      }
      else
      {
        const av::MeditMesh r = av::ParseMeditMeshBinary(s);
        for (std::int32_t id : r.Mesh.Cells)
          AV_CHECK(id >= 0 && static_cast<std::size_t>(id) < r.Mesh.NumPoints());
        AV_CHECK(
          r.CellRefs.size() == r.Mesh.NumCells() && r.PointRefs.size() == r.Mesh.NumPoints());
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

} // namespace

int TestMeditBinaryIO(int, char* argv[])
{
  TestLayout();
  TestRoundTrips();
  TestOtherVersions();
  TestFiles(argv[2]);
  TestErrors();
  TestFuzz();
  return AV_TEST_RESULT();
}
