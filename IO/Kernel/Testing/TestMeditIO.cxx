// SPDX-License-Identifier: BSD-3-Clause
// Tests the Medit .mesh/.sol reader and writer: content, tensor order, exact round trip,
// error messages with line numbers, and a fuzz loop (truncations / byte flips).
#include "MeditIO.h"
#include "AnisoTestChecks.h"

#include <cstdio>
#include <random>
#include <string>

namespace
{

const char* TetMesh = R"(# a comment line
MeshVersionFormatted 2
Dimension
3
Vertices
5
0 0 0 1
1 0 0 2
0 1 0 3
0 0 1 4   # trailing comment
1 1 1 5
Corners
2
1 2
Tetrahedra
2
1 2 3 4 10
2 3 4 5 20
Triangles
1
1 2 3 7
Edges
1
1 2 9
End
)";

const char* TriMesh2D = R"(MeshVersionFormatted 1
Dimension 2
Vertices 4
0 0 1  1 0 1  1 1 2  0 1 2
Triangles 2
1 2 3 5  1 3 4 6
End
)";

std::string MessageOf(const std::string& text, bool sol = false)
{
  try
  {
    if (sol)
    {
      av::ParseMeditSol(text, "f");
    }
    else
    {
      av::ParseMeditMesh(text, "f");
    }
  }
  catch (const av::InputError& e)
  {
    return e.what();
  }
  return "";
}

void TestContent()
{
  const av::MeditMesh m = av::ParseMeditMesh(TetMesh);
  AV_CHECK(m.Mesh.AmbientDim == 3 && m.Mesh.SimplexDim == 3);
  AV_CHECK(m.Mesh.NumPoints() == 5 && m.Mesh.NumCells() == 2);
  AV_CHECK(m.PointRefs.size() == 5 && m.PointRefs[4] == 5);
  AV_CHECK(m.CellRefs.size() == 2 && m.CellRefs[0] == 10 && m.CellRefs[1] == 20);
  AV_CHECK(m.Mesh.Cell(1)[0] == 1 && m.Mesh.Cell(1)[3] == 4); // 1-based -> 0-based
  AV_CHECK(m.Mesh.Point(4)[2] == 1.0);
  AV_CHECK(m.Faces.size() == 3 && m.FaceRefs.size() == 1 && m.FaceRefs[0] == 7);
  AV_CHECK(m.Edges.size() == 2 && m.EdgeRefs[0] == 9 && m.Edges[1] == 1);
  AV_CHECK(m.IgnoredKeywords.empty());
  AV_CHECK((m.Corners == std::vector<std::int32_t>{ 0, 1 }) && m.Ridges.empty());

  // Ridges (indices into Edges, which may come later) and Corners survive a round trip; a
  // ridge index past the edges or a corner past the vertices is an error naming the section.
  const std::string ridged =
    std::string(TetMesh).replace(std::string(TetMesh).find("Tetrahedra"), 0, "Ridges\n1\n1\n");
  const av::MeditMesh r = av::ParseMeditMesh(ridged, "r");
  AV_CHECK(r.Ridges == std::vector<std::int32_t>{ 0 });
  const av::MeditMesh back = av::ParseMeditMesh(av::FormatMeditMesh(r), "back");
  AV_CHECK(back.Ridges == r.Ridges && back.Corners == r.Corners && back.Edges == r.Edges);
  std::string badRidge = ridged;
  badRidge.replace(badRidge.find("Ridges\n1\n1"), 11, "Ridges\n1\n2");
  AV_CHECK(MessageOf(badRidge).find("Ridges") != std::string::npos);
  std::string badCorner = std::string(TetMesh);
  badCorner.replace(badCorner.find("Corners\n2\n1 2"), 14, "Corners\n2\n1 9");
  AV_CHECK(MessageOf(badCorner).find("Corners") != std::string::npos);

  const av::MeditMesh t = av::ParseMeditMesh(TriMesh2D);
  AV_CHECK(t.Mesh.AmbientDim == 2 && t.Mesh.SimplexDim == 2);
  AV_CHECK(t.Mesh.NumPoints() == 4 && t.Mesh.NumCells() == 2);
  AV_CHECK(t.Mesh.Point(2)[0] == 1.0 && t.Mesh.Point(2)[1] == 1.0);
  AV_CHECK(t.CellRefs[1] == 6 && t.Mesh.Cell(1)[2] == 3);
  AV_CHECK(t.Version == 1);
}

void TestTensorOrder()
{
  // all six values distinct: any swap of components is caught
  const av::MeditSol s3 = av::ParseMeditSol(
    "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 3\n11 21 22 31 32 33\nEnd\n");
  AV_CHECK(s3.NumVertices == 1 && s3.FieldTypes.size() == 1 && s3.FieldTypes[0] == 3);
  const double expect3[6] = { 11, 22, 33, 21, 32, 31 }; // XX YY ZZ XY YZ XZ
  for (int j = 0; j < 6; ++j)
  {
    AV_CHECK_MSG(s3.Fields[0][j] == expect3[j], "3D component " << j);
  }
  const av::MeditSol s2 = av::ParseMeditSol(
    "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n1\n1 3\n11 21 22\nEnd\n");
  const double expect2[6] = { 11, 22, 0, 21, 0, 0 };
  for (int j = 0; j < 6; ++j)
  {
    AV_CHECK_MSG(s2.Fields[0][j] == expect2[j], "2D component " << j);
  }
  // writing converts back: the file text holds the Medit order
  const std::string text = av::FormatMeditSol(s3);
  AV_CHECK_MSG(text.find("11 21 22 31 32 33") != std::string::npos, text);

  // scalar sol = size h -> M = I / h^2; mixed fields keep their own layout
  const av::MeditSol sc = av::ParseMeditSol(
    "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n2 1 2\n0.5 1 2 3\n0.25 4 5 6\nEnd\n");
  AV_CHECK(sc.Fields[1].size() == 6 && sc.Fields[1][5] == 6.0);
  const av::MetricField mf = av::MetricFromMeditSol(sc, 0);
  AV_CHECK(mf.NumPoints() == 2);
  AV_CHECK(mf.At(0)[0] == 4.0 && mf.At(0)[1] == 4.0 && mf.At(0)[2] == 4.0 && mf.At(0)[3] == 0.0);
  AV_CHECK(mf.At(1)[2] == 16.0 && mf.At(1)[5] == 0.0);
  AV_CHECK_THROWS(av::MetricFromMeditSol(sc, 1)); // vector field
  AV_CHECK_THROWS(av::MetricFromMeditSol(sc, 2)); // no such field
  const av::MeditSol neg =
    av::ParseMeditSol("MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n1 1\n-0.5\nEnd\n");
  AV_CHECK_THROWS(av::MetricFromMeditSol(neg));
}

void TestExactRoundTrip()
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  av::MeditMesh m;
  m.Mesh.AmbientDim = 3;
  m.Mesh.SimplexDim = 3;
  const int np = 50;
  for (int i = 0; i < np * 3; ++i)
  {
    m.Mesh.Points.push_back(u(rng) * (i % 7 == 0 ? 1e-300 : 1e5) + 0.1);
  }
  for (int c = 0; c < 40; ++c)
  {
    for (int j = 0; j < 4; ++j)
    {
      m.Mesh.Cells.push_back(static_cast<std::int32_t>((c * 7 + j * 13) % np));
    }
    m.CellRefs.push_back(c - 20);
  }
  for (int i = 0; i < np; ++i)
  {
    m.PointRefs.push_back(i * 3);
  }
  m.Faces = { 0, 1, 2 };
  m.FaceRefs = { -4 };
  av::MetricField metric;
  for (int i = 0; i < np * 6; ++i)
  {
    metric.Values.push_back(u(rng) / 3.0);
  }

  const std::string meshFile = "TestMeditIO_roundtrip.mesh", solFile = "TestMeditIO_roundtrip.sol";
  av::WriteMeditMesh(meshFile, m);
  av::WriteMeditSol(solFile, av::MeditSolFromMetric(metric, 3));
  const av::MeditMesh r = av::ReadMeditMesh(meshFile);
  const av::MetricField rm = av::MetricFromMeditSol(av::ReadMeditSol(solFile));
  std::remove(meshFile.c_str());
  std::remove(solFile.c_str());
  AV_CHECK(r.Mesh.Points == m.Mesh.Points); // bitwise-exact doubles
  AV_CHECK(r.Mesh.Cells == m.Mesh.Cells);
  AV_CHECK(r.PointRefs == m.PointRefs && r.CellRefs == m.CellRefs);
  AV_CHECK(r.Faces == m.Faces && r.FaceRefs == m.FaceRefs);
  AV_CHECK(rm.Values == metric.Values);

  // 2D: XX YY XY survive, the rest is dropped
  av::MetricField m2;
  m2.Values = { 0.1, 0.2, 0.3, 0.4, 0.5, 0.6 };
  const av::MetricField r2 =
    av::MetricFromMeditSol(av::ParseMeditSol(av::FormatMeditSol(av::MeditSolFromMetric(m2, 2))));
  AV_CHECK(r2.Values.size() == 6 && r2.Values[0] == 0.1 && r2.Values[1] == 0.2 &&
           r2.Values[3] == 0.4);
  AV_CHECK(r2.Values[2] == 0.0 && r2.Values[4] == 0.0 && r2.Values[5] == 0.0);

  // SimplexMesh overload, 2D triangles
  const av::MeditMesh t = av::ParseMeditMesh(TriMesh2D);
  const av::MeditMesh t2 =
    av::ParseMeditMesh(av::FormatMeditMesh(t.Mesh, t.PointRefs.data(), t.CellRefs.data()));
  AV_CHECK(t2.Mesh.Points == t.Mesh.Points && t2.Mesh.Cells == t.Mesh.Cells &&
           t2.CellRefs == t.CellRefs);
}

void TestErrors()
{
  const std::string head = "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 1\n";
  // line numbers are named
  std::string msg = MessageOf(head + "0 abc 0 1\nEnd\n");
  AV_CHECK_MSG(msg.find("f:6:") == 0 && msg.find("abc") != std::string::npos, msg);
  msg = MessageOf(head + "0 nan 0 1\nEnd\n");
  AV_CHECK_MSG(msg.find("f:6:") == 0 && msg.find("finite") != std::string::npos, msg);
  msg = MessageOf(head + "0 0 0 1\nTriangles\n1\n1 2 3 0\nEnd\n");
  AV_CHECK_MSG(msg.find("f:9:") == 0, msg); // vertex 3 of 2
  msg = MessageOf(head + "0 0 0 1\nTriangles\n1\n0 1 2 0\nEnd\n");
  AV_CHECK_MSG(msg.find("f:9:") == 0, msg); // Medit ids are 1-based
  msg = MessageOf(head + "0 0 0 1\nTriangles\n1\n1 -2 1 0\nEnd\n");
  AV_CHECK_MSG(msg.find("f:9:") == 0, msg);
  msg = MessageOf(head);
  AV_CHECK_MSG(msg.find("f:4:") == 0 && msg.find("truncated") != std::string::npos, msg);
  msg = MessageOf(head + "0 0\n# padding comment so that the byte bound does not trigger first\n");
  AV_CHECK_MSG(msg.find("f:8:") == 0 && msg.find("end of file") != std::string::npos, msg);
  // huge counts are refused before allocating
  msg = MessageOf("MeshVersionFormatted 2\nDimension 3\nVertices\n2000000000\n0 0 0 1\nEnd\n");
  AV_CHECK_MSG(msg.find("f:4:") == 0 && msg.find("truncated") != std::string::npos, msg);
  AV_CHECK_THROWS(av::ParseMeditMesh("Dimension 3\nVertices\n1000000000000\n"));
  AV_CHECK_THROWS(av::ParseMeditSol("Dimension 3\nSolAtVertices\n2000000000\n1 3\n1 2 3\nEnd\n"));
  // structure
  AV_CHECK_THROWS(av::ParseMeditMesh(head + "0 0 0 1\nTriangles\n1\n1 2 1 0\n"));   // no End
  AV_CHECK_THROWS(av::ParseMeditMesh(head + "0 0 0 1\nEnd\n"));                     // no cells
  AV_CHECK_THROWS(av::ParseMeditMesh("Dimension 3\nTriangles\n1\n1 2 3 0\nEnd\n")); // no vertices
  AV_CHECK_THROWS(av::ParseMeditMesh("Dimension 4\nEnd\n"));
  AV_CHECK_THROWS(av::ParseMeditMesh("Vertices\n1\n0 0 0 0\nEnd\n")); // no Dimension
  AV_CHECK_THROWS(av::ParseMeditMesh(
    "Dimension 2\nVertices 4\n0 0 0 1 0 0 0 1 0 1 1 0\nTetrahedra 1\n1 2 3 4 0\nEnd\n"));
  msg = MessageOf("Dimension 3\nTriangles\n1\n1 2 3 0\nVertices\n2\n0 0 0 0\n1 1 1 0\nEnd\n");
  AV_CHECK_MSG(msg.find("f:2:") == 0 && msg.find("vertex 3") != std::string::npos, msg);
  AV_CHECK_THROWS(av::ParseMeditSol("Dimension 3\nSolAtVertices\n1\n1 4\n1\nEnd\n")); // bad type
  AV_CHECK_THROWS(av::ParseMeditSol("Dimension 3\nSolAtVertices\n2\n1 3\n1 2 3 4 5 6\nEnd\n"));
  AV_CHECK_THROWS(av::ParseMeditSol("Dimension 3\nEnd\n"));
  AV_CHECK_THROWS(av::ReadMeditMesh("/nonexistent/dir/x.mesh"));
  AV_CHECK_THROWS(av::ParseMeditMesh(std::string("\1\0\0\0\2\0\0\0", 8)));
  // writer refuses inconsistent input instead of writing an unreadable file
  av::SimplexMesh bad;
  bad.AmbientDim = 3;
  bad.SimplexDim = 2;
  bad.Points = { 0, 0, 0, 1, 0, 0 };
  bad.Cells = { 0, 1, 2 };
  AV_CHECK_THROWS(av::FormatMeditMesh(bad));
}

/// Random truncations and byte flips: each input must parse or throw InputError, and a
/// parsed mesh must be internally consistent.
void TestFuzz()
{
  const std::string valid = av::FormatMeditMesh(av::ParseMeditMesh(TetMesh)) + "";
  const std::string validSol =
    "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n2\n2 3 1\n1 2 3 4 5 6 0.5\n"
    "6 5 4 3 2 1 0.25\nEnd\n";
  std::mt19937 rng(12345);
  const char bytes[] = "0123456789-+.eE #\n\t aZ\0\xff";
  int parsed = 0, rejected = 0;
  for (int it = 0; it < 4000; ++it)
  {
    const bool sol = (it % 2) == 1;
    std::string s = sol ? validSol : valid;
    const int mode = static_cast<int>(rng() % 3);
    if (mode == 0 || mode == 2)
    {
      s.resize(rng() % (s.size() + 1));
    }
    if (mode >= 1)
    {
      const int flips = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < flips && !s.empty(); ++k)
      {
        s[rng() % s.size()] = bytes[rng() % (sizeof(bytes) - 1)];
      }
    }
    try
    {
      if (sol)
      {
        const av::MeditSol r = av::ParseMeditSol(s);
        for (std::size_t f = 0; f < r.Fields.size(); ++f)
        {
          AV_CHECK(r.Fields[f].size() == r.NumVertices * r.FieldComponents(r.FieldTypes[f]));
        }
      }
      else
      {
        const av::MeditMesh r = av::ParseMeditMesh(s);
        for (std::int32_t id : r.Mesh.Cells)
        {
          AV_CHECK(id >= 0 && static_cast<std::size_t>(id) < r.Mesh.NumPoints());
        }
        AV_CHECK(r.CellRefs.size() == r.Mesh.NumCells() &&
                 r.PointRefs.size() == r.Mesh.NumPoints());
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

int TestMeditIO(int, char*[])
{
  TestContent();
  TestTensorOrder();
  TestExactRoundTrip();
  TestErrors();
  TestFuzz();
  return AV_TEST_RESULT();
}
