// SPDX-License-Identifier: BSD-3-Clause
// TriangleMeshImprover: the triangle half of ImproveMesh (2-2 edge flips, smoothing, edge
// collapses and splits) for flat 2D domains and surfaces, on a SimplexStarMesh<2> (mutable
// triangle list with vertex-to-triangle stars) with an undo journal for compound operations.
#ifndef av_TriangleMeshImprover_h
#define av_TriangleMeshImprover_h

#include "MeshImprovement.h"
#include "SimplexStarMesh.h"
#include "VertexStarSmoother.h"

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace av
{

class TriangleMeshImprover
{
public:
  /// `sqrtMetrics`: one symmetric square root per point (2D: the 2x2 one padded with zeros);
  /// `fixed`: per point, nonzero = never moves (FeatureLinePoint: slides along its line on a
  /// surface when Options.ProjectToFeatureLine is set).
  TriangleMeshImprover(SimplexMesh& mesh,
    std::vector<Eigen::Matrix3d> sqrtMetrics,
    const std::vector<std::uint8_t>* fixed,
    const MeshImprovementOptions& options);

  /// Runs the passes, writes the triangles and points back into the mesh, fills the counts.
  void Run(MeshImprovementResult& result);

private:
  using Tri = SimplexStarMesh<2>::Simplex;

  /// What a compound operation (collapse or split, then smoothing and flips) changed, so that
  /// it can be undone when the worst quality it touches does not rise.
  struct Journal
  {
    struct Vertex
    {
      std::int32_t Id;
      Eigen::Vector3d P, N;
      Eigen::Matrix3d S;
    };
    bool Active = false;
    std::vector<std::pair<std::int32_t, Tri>> Tris;
    std::vector<std::pair<std::int32_t, std::vector<std::int32_t>>> Stars;
    std::vector<Vertex> Vertices;
    std::vector<std::int32_t> Touched; // triangles whose quality the operation may change
    double WorstBefore = 0.0;          // their worst quality before it
    std::size_t NumTris = 0, NumPoints = 0, Flips = 0, Smoothed = 0;
  };

  double Quality(const Tri& t) const { return Work.Quality(t); }
  bool Alive(std::int32_t t) const { return Work.IsAlive(t); }
  void MarkBoundaryAndNonManifold();
  std::int32_t OtherTriangle(std::int32_t tri, std::int32_t a, std::int32_t b, int* count) const;
  bool Place(std::int32_t v, std::int32_t near, const Eigen::Vector3d& x);

  // Mutations (journaled while a compound operation runs).
  void Touch(std::int32_t t);
  void SetTri(std::int32_t t, const Tri& tri);
  std::int32_t AddTri(const Tri& tri);
  void StarErase(std::int32_t v, std::int32_t t);
  void StarAdd(std::int32_t v, std::int32_t t);
  void SaveVertex(std::int32_t v);
  std::int32_t AddVertex(const Eigen::Vector3d& p,
    const Eigen::Matrix3d& s,
    const Eigen::Vector3d& n,
    bool fixed,
    std::int32_t hint);
  void Begin();
  void Rollback();
  bool Commit();
  bool FinishCompound(std::int32_t center);

  bool TryFlip(std::int32_t tri, int edge);
  bool TrySmooth(std::int32_t v);
  bool TryCollapse(std::int32_t tri);
  bool CollapseInto(std::int32_t keep, std::int32_t remove);
  bool TrySplit(std::int32_t tri);
  bool Improve(std::int32_t tri, double target);
  bool Accepts(double after, double before) const;

  SimplexMesh& Mesh;
  bool Surface;
  MeshImprovementOptions Options;
  SimplexStarMesh<2> Work;
  // Short names for the working mesh's arrays, which the journal saves and restores.
  std::vector<Eigen::Vector3d>& P;
  std::vector<Eigen::Vector3d>& N; // unit domain normals (2D: +z), orient the triangles
  std::vector<Eigen::Matrix3d>& S;
  std::vector<Tri>& Tris; // in place; a removed triangle is {-1, -1, -1}
  std::vector<std::vector<std::int32_t>>& Star;
  std::vector<char>& Fixed;
  std::vector<std::uint8_t>& Moved;
  std::vector<std::int32_t> Hint; // a vertex the caller knows, near each one (PlacePoint's near)
  /// Feature-line vertices that slide along their line (ProjectToFeatureLine); still Fixed for
  /// flips, collapses and splits.
  std::vector<char> Slides;
  VertexStarSmoother<2> Smoother;
  Journal Undo;
  double CosFlipDihedral = 0.0;
  std::size_t Flips = 0, Smoothed = 0, Splits = 0, Collapses = 0;
};

} // namespace av

#endif
