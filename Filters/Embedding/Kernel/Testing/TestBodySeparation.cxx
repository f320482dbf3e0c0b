// SPDX-License-Identifier: BSD-3-Clause
// Bodies apart in the embedding: two cubes that touch along a face without shared points (a
// contact assembly) come out of the solver with the input coordinates unchanged, every length
// inside a body unchanged, and points of different bodies at least the largest body's diameter
// apart; one body and SeparateBodies off leave the embedding as solved.
#include "AnalyticMetrics.h"
#include "BodySeparation.h"
#include "EmbeddingSolver.h"
#include "InputError.h"
#include "MeshTopology.h"
#include "StructuredMeshes.h"
#include "AnisoTestChecks.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
using namespace av;

double Distance(const Embedding& e, std::size_t a, std::size_t b)
{
  double d2 = 0.0;
  for (int d = 0; d < e.Dim; ++d)
    d2 += (e.At(a)[d] - e.At(b)[d]) * (e.At(a)[d] - e.At(b)[d]);
  return std::sqrt(d2);
}

// Two 4 x 4 x 4 grids: [0,1]^3 and [0,1]^2 x [1,2], the second with its own copy of z = 1.
SimplexMesh TouchingCubes()
{
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 }, lo2[3] = { 0, 0, 1 }, hi2[3] = { 1, 1, 2 };
  SimplexMesh m = MakeKuhnTetGrid(4, 4, 4, lo, hi);
  const SimplexMesh b = MakeKuhnTetGrid(4, 4, 4, lo2, hi2);
  const std::int32_t offset = static_cast<std::int32_t>(m.NumPoints());
  m.Points.insert(m.Points.end(), b.Points.begin(), b.Points.end());
  for (std::int32_t id : b.Cells)
    m.Cells.push_back(id + offset);
  return m;
}
} // namespace

int TestBodySeparation(int, char*[])
{
  const SimplexMesh mesh = TouchingCubes();
  std::vector<std::int32_t> body;
  AV_CHECK(LabelBodies(mesh, body) == 2u);
  const MetricField metric = EvaluateAnalyticMetric(AnalyticPreset::Cube1, mesh);
  EmbeddingOptions o;
  o.Iterations = 5;
  o.MaxIterations = 5;
  o.SeparateBodies = false;
  const EmbeddingResult joined = ComputeEmbedding(mesh, metric, o);
  o.SeparateBodies = true;
  const EmbeddingResult apart = ComputeEmbedding(mesh, metric, o);
  AV_CHECK(joined.NumBodies == 2u && apart.NumBodies == 2u);
  const std::size_t n = mesh.NumPoints();
  // Input coordinates exactly kept; the two touching faces coincide when joined.
  bool inputKept = true;
  for (std::size_t p = 0; p < n; ++p)
    for (int d = 0; d < 3; ++d)
      inputKept = inputKept && apart.Embedded.At(p)[d] == mesh.Points[3 * p + d];
  AV_CHECK(inputKept);
  // Lengths inside each body unchanged (the same solve, then a translation per body).
  double worstChange = 0.0, diameter = 0.0, closest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b)
    {
      const double d = Distance(apart.Embedded, a, b);
      if (body[a] == body[b])
      {
        worstChange = std::max(worstChange, std::abs(d - Distance(joined.Embedded, a, b)));
        diameter = std::max(diameter, d);
      }
      else
        closest = std::min(closest, d);
    }
  AV_CHECK_MSG(worstChange < 1e-12, "a length inside a body changed by " << worstChange);
  AV_CHECK_MSG(closest >= diameter, "bodies " << closest << " apart, diameter " << diameter);
  // Joined, the copies of the z = 1 face lie at the same input point: not apart.
  double joinedClosest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < n / 2; ++a)
    for (std::size_t b = n / 2; b < n; ++b)
      joinedClosest = std::min(joinedClosest, Distance(joined.Embedded, a, b));
  AV_CHECK_MSG(joinedClosest < 0.5 * diameter, "joined bodies " << joinedClosest << " apart");

  // One body: nothing moves. Bad input: wrong label count, no extra coordinate.
  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const SimplexMesh cube = MakeKuhnTetGrid(4, 4, 4, lo, hi);
  const MetricField cubeMetric = EvaluateAnalyticMetric(AnalyticPreset::Cube1, cube);
  o.SeparateBodies = true;
  const EmbeddingResult one = ComputeEmbedding(cube, cubeMetric, o);
  o.SeparateBodies = false;
  const EmbeddingResult oneOff = ComputeEmbedding(cube, cubeMetric, o);
  AV_CHECK(one.NumBodies == 1u && one.Embedded.Coords == oneOff.Embedded.Coords);
  Embedding e = apart.Embedded;
  AV_CHECK_THROWS(SeparateBodies(std::vector<std::int32_t>(3, 0), 1, 3, e));
  AV_CHECK_THROWS(SeparateBodies(body, 2, e.Dim, e));
  return AV_TEST_RESULT();
}
