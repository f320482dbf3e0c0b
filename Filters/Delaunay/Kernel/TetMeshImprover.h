// SPDX-License-Identifier: BSD-3-Clause
// TetMeshImprover: the tetrahedral half of ImproveMesh (edge removal, 2-3 flips, smoothing) on a
// SimplexStarMesh<3> (mutable tet list with vertex-to-tet stars).
#ifndef av_TetMeshImprover_h
#define av_TetMeshImprover_h

#include "MeshImprovement.h"
#include "SimplexStarMesh.h"
#include "VertexStarSmoother.h"

#include <Eigen/Dense>

#include <array>
#include <vector>

namespace av
{

class TetMeshImprover
{
public:
  /// `sqrtMetrics`: one symmetric square root per point; `fixed`: per point, nonzero = never
  /// moves (FeatureLinePoint: except along a straight crease).
  TetMeshImprover(SimplexMesh& mesh,
    std::vector<Eigen::Matrix3d> sqrtMetrics,
    const std::vector<std::uint8_t>* fixed,
    const MeshImprovementOptions& options);

  /// Runs the passes, writes the tets and points back into the mesh, fills the counts.
  void Run(MeshImprovementResult& result);

private:
  using Tet = SimplexStarMesh<3>::Simplex;

  double Quality(const Tet& t) const { return Work.Quality(t); }
  void MarkBoundaryAndNonManifold(const std::vector<std::uint8_t>* userFlags);
  /// Frees the boundary vertices whose boundary faces form one disc around them and lie in one
  /// plane (PlaneNormal set) or in two planes meeting along a straight crease through them
  /// (CreaseDirection set), given the faces of one tet with their outward order. `flags`: per
  /// vertex 0 free, FeatureLinePoint (may only slide on a crease), other values stay.
  void FindMovableBoundaryVertices(const std::vector<std::array<std::int32_t, 3>>& boundary,
    const std::vector<std::uint8_t>& flags);
  /// Boundary vertex v (link faces `link`, mean normal `meanNormal`) that neither is planar nor
  /// smooth, by the domain's boundary: SnapToBoundary marks it off the domain's boundary if
  /// ProjectToBoundary puts it elsewhere. Its one move is then
  /// TrySnap; it stays fixed once snapped. InputBoundaryMoves: if v is on the domain's boundary
  /// and its faces form one disc (`disc`), it moves as a curved-patch vertex instead.
  void ClassifyByDomainBoundary(std::int32_t v,
    const Eigen::Vector3d& meanNormal,
    const std::vector<std::pair<std::int32_t, std::int32_t>>& link,
    bool disc);
  bool TrySnap(std::int32_t v);
  /// The unit direction of the straight crease through v whose link faces, in disc order, are
  /// `order` (indices into `link`); zero if the disc is not two planar fans meeting on a line
  /// through v with v's two crease neighbours on it, one on each side.
  Eigen::Vector3d CreaseDirection(std::int32_t v,
    const std::vector<std::pair<std::int32_t, std::int32_t>>& link,
    const std::vector<std::size_t>& order) const;
  bool Improve(std::int32_t tet); // best operation on one bad tet, true if applied
  /// MeshImprovementOptions::MeanSmoothingSweeps after the worst-first passes.
  void MeanSmoothingSweeps();
  bool TryEdgeRemoval(std::int32_t a, std::int32_t b);
  /// The tets on edge (a, b) into EdgeTets and, per tet, its other two vertices (c, d) with
  /// (a, b, c, d) even into Next; returns their count.
  std::size_t CollectEdgeLink(std::int32_t a, std::int32_t b);
  /// The d of the one pair (v, d) among the first n of Next; -1 if none or several.
  std::int32_t Successor(std::int32_t v, std::size_t n) const;
  bool BuildRing(std::int32_t a, std::int32_t b);
  /// As BuildRing for a boundary edge: the link is a path r0..rn (n tets), and the edge's two
  /// boundary faces (a, b, r0) and (a, b, rn) are coplanar, or within BoundaryFlipMaxDihedral
  /// of it (then `curved`). False otherwise.
  bool BuildOpenRing(std::int32_t a, std::int32_t b, bool& curved);
  double Volume(const Tet& t) const; // Euclidean, times 6
  double StarVolume(std::int32_t v) const; // of v's star, Euclidean, times 6
  /// Keeps a boundary vertex's move from `start` (AcceptMove, the curved-patch volume budget
  /// with the star's volume `volumeBefore`), or puts v back at `start` and returns false.
  bool KeepBoundaryMove(std::int32_t v, const Eigen::Vector3d& start, double volumeBefore);
  bool TryFlip23(std::int32_t tet, int apexIndex, double worst);
  bool TrySmooth(std::int32_t v);
  /// Vertex insertion in bad tet `tet` (MeshImprovementOptions::Insertions): the best of a few
  /// trial points, each with its cavity, joined and smoothed, then undone; the best is redone.
  bool TryInsertion(std::int32_t tet);
  /// Removes bad tet `tet` if it has exactly two boundary faces (PeelBoundaryTets).
  bool TryPeel(std::int32_t tet);
  /// TryPeel of a tet with three boundary faces (`inner`: the tet across its fourth).
  bool PeelEar(std::int32_t tet, std::int32_t inner);
  /// Removes boundary tet `tet` if `after` (the worst tet left) beats `before` and the peel
  /// budget allows its volume.
  bool CommitPeel(std::int32_t tet, double after, double before);
  /// Edge contraction in bad tet `tet` (MeshImprovementOptions::Collapses): an interior free
  /// end of one of its edges, shortest metric edge first, merged into the other end.
  bool TryContraction(std::int32_t tet);
  /// Merges interior vertex `remove` into `keep` (which stays where it is): the tets on the edge
  /// die, the rest of remove's star is joined to keep. Applied only if every new tet is positive
  /// (then they tile remove's old star exactly: volume and boundary unchanged), no face is left
  /// in more than two tets, no new edge already exists and the worst tet touched gets better.
  bool ContractInto(std::int32_t keep, std::int32_t remove);
  bool OnBoundary(std::int32_t v) const; // a boundary face contains v
  /// The cavity of point x seeded with `seed` into Cavity and its boundary faces (outward, in
  /// their tets' order) into CavityFaces: the tets across interior faces whose circumspheres,
  /// mapped by `map`, contain x, then shrunk until x sees every boundary face. False if x cannot
  /// see the seed's faces or a vertex would be left inside.
  bool BuildCavity(std::int32_t seed, const Eigen::Vector3d& x, const Eigen::Matrix3d& map);
  void CollectCavityFaces();
  /// The tet sharing the face opposite vertex index m of tet t; -1 on the boundary (or where
  /// more than one does).
  std::int32_t Across(std::int32_t t, int m) const;
  /// Replaces Cavity by the tets joining a new point (x, metric root s) to CavityFaces; returns
  /// the point's id. UndoInsertion reverses it exactly.
  std::int32_t ApplyInsertion(const Eigen::Vector3d& x, const Eigen::Matrix3d& s);
  void UndoInsertion(std::int32_t point, std::size_t firstNewTet);
  bool Accepts(double after, double before) const;
  bool OutOfRange(std::int32_t a, std::int32_t b) const; // metric length vs the median
  int OutOfRangeAround(std::int32_t v) const;            // among v's edges (with repeats)
  void ComputeMedianEdgeLength();

  SimplexMesh& Mesh;
  MeshImprovementOptions Options;
  SimplexStarMesh<3> Work;
  // Short names for the working mesh's arrays (changed only through Work.Add and Work.Kill).
  const std::vector<Eigen::Vector3d>& P;
  const std::vector<Tet>& Tets;
  const std::vector<std::vector<std::int32_t>>& Star; // vertex -> alive tets
  VertexStarSmoother<3> Smoother;
  // Scratch of the edge removal (no allocation per operation once grown).
  std::vector<std::int32_t> EdgeTets, Ring, Next;
  std::vector<double> Best;
  std::vector<int> Choice;
  // Scratch of the insertion: the cavity's tets (and what they held, for the undo) and faces.
  std::vector<std::int32_t> Cavity;
  std::vector<Tet> CavityTets;
  std::vector<std::array<std::int32_t, 3>> CavityFaces;
  std::vector<std::int32_t> CavityFaceOwner;
  // Scratch of the snap: the free interior neighbours, and those moved with their old position.
  std::vector<std::int32_t> SnapNeighbours;
  std::vector<std::pair<std::int32_t, Eigen::Vector3d>> SnapMoved;
  // Scratch of the contraction: the new tets, and the faces on `keep` after it.
  std::vector<Tet> ContractedTets;
  std::vector<std::array<std::int32_t, 3>> ContractedFaces;
  // Per point: the unit normal of its boundary plane where it may move in it, else zero;
  // Curved: the plane is a tangent plane and ProjectToBoundary puts the point on the surface.
  std::vector<Eigen::Vector3d> PlaneNormal;
  std::vector<char> Curved;
  // SnapToBoundary: a boundary vertex not on the domain's boundary, not snapped yet (1 + the
  // snaps tried); 0 otherwise.
  std::vector<char> OffBoundary;
  // Per point: the unit direction of its straight crease where it may slide along it, else zero.
  std::vector<Eigen::Vector3d> LineDirection;
  bool EdgeRuleWaived = false; // the tet being improved is below EdgeLengthRuleMinAngle
  std::size_t Flips23 = 0, EdgeRemovals = 0, Smoothed = 0;
  std::size_t BoundaryEdgeRemovals = 0, BoundarySmoothed = 0, CreaseSmoothed = 0;
  std::size_t Insertions = 0, Peels = 0, Snaps = 0, Contractions = 0, MeanSmoothed = 0;
  double PeeledVolume = 0.0;                           // Euclidean, times 6
  double MeshVolume = 0.0, BoundaryVolumeChange = 0.0; // Euclidean, times 6
  double MedianEdge = 0.0; // median metric edge length of the input mesh
};

} // namespace av

#endif
