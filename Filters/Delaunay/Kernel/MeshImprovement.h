// SPDX-License-Identifier: BSD-3-Clause
// MeshImprovement: flips and vertex smoothing that raise the worst element of a simplicial mesh,
// measured in the metric (Klingner & Shewchuk 2007, "Aggressive tetrahedral mesh improvement":
// tets also get vertex insertion, triangles edge collapses and splits). Runs on the final dual
// mesh of the meshing pipeline.
#ifndef av_MeshImprovement_h
#define av_MeshImprovement_h

#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace av
{

/// In ImproveMesh's `fixedPoints`: 0 free, any other value never moves, except this one: a point
/// on a feature line (the sampler's FeatureKind 1). With StraightCreases it slides along the line
/// where the tets' boundary around it is two planes meeting in a straight line through it.
constexpr std::uint8_t FeatureLinePoint = 2;

/// Options of ImproveMesh.
struct MeshImprovementOptions
{
  int MaxPasses = 4; ///< passes over the bad elements; a pass that changes nothing ends the run
  /// Elements whose quality (smallest metric angle, see MetricSimplexQuality) is below this
  /// angle, in degrees, are worked on; the others are only touched by their neighbors' moves.
  double TargetAngle = 35.0;
  bool Flips = true;     ///< tets: 2-3 flips and edge removal (3-2 flips included); triangles: 2-2
  bool Smoothing = true; ///< interior vertex moves that raise the worst incident element
  /// Sweeps over the vertices after the worst-first passes, each moving every free vertex
  /// (tets: also those that may move in a boundary plane or along a straight crease; not on
  /// curved patches) where that raises the mean §5.2 shape measure G of its star without
  /// lowering its worst element or adding out-of-range edges (VertexStarSmoother::
  /// TryMeanSmooth). 0: none (the worst-first passes alone, as before 2026-12-07).
  int MeanSmoothingSweeps = 2;
  /// Tets: also work on planar parts of the boundary, where that keeps the domain exactly: a
  /// boundary vertex whose boundary faces all lie in one plane (and form one disc) moves in that
  /// plane, and a boundary edge whose two boundary faces are coplanar is removed like an
  /// interior one (the 2-2 / 4-4 boundary flips and their longer cousins), the polygon of its
  /// open ring triangulated anew. Creases, corners and curved patches stay untouched.
  bool PlanarBoundary = true;
  /// Tets, with PlanarBoundary: a boundary edge is also removed where its two boundary faces
  /// meet at up to this angle (degrees) away from coplanar, on a curved boundary. That moves the
  /// boundary by the thin tet between the old and the new faces (their four vertices stay where
  /// they are, on the input's boundary); 0: planar patches only. Far below the feature angle.
  double BoundaryFlipMaxDihedral = 10.0;
  /// Tets: the most volume those curved-boundary operations (removals and the moves below) may
  /// change in all, as a fraction of the mesh's volume.
  double BoundaryFlipVolumeBudget = 5e-3;
  /// Tets, with PlanarBoundary: puts a trial position x (3 values) of boundary vertex v on the
  /// domain's boundary surface, near the tangent plane with unit inward normal `normal`: writes
  /// `placed` and, if `surfaceNormal` is not null, the surface's unit normal there (oriented as
  /// `normal`); false when there is no such point (another sheet of a thin part). With it, a
  /// vertex of a smooth curved patch (one disc of boundary faces, all within
  /// BoundaryFlipMaxDihedral of their mean plane) moves too: in that plane, then onto the
  /// surface. Empty: those vertices stay.
  std::function<bool(
    std::int32_t v, const double* x, const double* normal, double* placed, double* surfaceNormal)>
    ProjectToBoundary;
  /// Tets, with ProjectToBoundary: a boundary vertex of the mesh that is not on the domain's
  /// boundary (a site just inside the domain whose cell meets the boundary: the mesh's boundary
  /// folds in through it) moves onto its closest point of the domain's boundary, its free
  /// interior neighbours smoothed after it, when that raises the worst tet of their stars and
  /// leaves no more of them below EdgeLengthRuleMinAngle; it then stays there. The change of
  /// volume brings the mesh closer to the domain and is not charged to BoundaryFlipVolumeBudget.
  bool SnapToBoundary = true;
  /// Tets, with ProjectToBoundary: a boundary vertex that lies on the domain's boundary, its
  /// boundary faces one disc but folded or chamfered (neither planar nor within
  /// BoundaryFlipMaxDihedral of their mean plane: the dual's boundary there is not the
  /// domain's), moves as a vertex of a smooth curved patch, in the domain's tangent plane at it
  /// and then onto the domain's boundary, within BoundaryFlipVolumeBudget. Feature sites stay.
  bool InputBoundaryMoves = true;
  /// Tets, with PlanarBoundary: a boundary vertex (free or FeatureLinePoint) whose boundary
  /// faces form one disc made of two planar fans that meet along a straight line through it,
  /// its two crease edges on that line, moves along the line. Both planes and the crease stay
  /// exactly where they are.
  bool StraightCreases = true;
  int MaxEdgeRemovalRing = 7; ///< edge removal on edges of at most this many tets (3 = 3-2 only)
  /// Tets: an operation may not add edges whose metric length, divided by the median of the
  /// input's, leaves [1/sqrt2, sqrt2] (the UGAWG range of the §5.2 evaluation): a flip's new
  /// edges must not be more often out of range than the edges it removes, a move may not raise
  /// the count among the vertex's edges.
  bool KeepEdgeLengths = true;
  /// Tets: KeepEdgeLengths binds operations on tets whose quality angle is at least this
  /// (degrees); a tet below it may be improved at the price of out-of-range edges (the real
  /// volumes' worst tets are otherwise stuck), and only such tets get the insertion, the
  /// contraction and the peel. 20°: the θ_min bar of issue 13 (15° until 2026-12-06: the §5.2
  /// bar of a bad tet; the presets' edges in range change by at most 0.03 points). 0: always.
  double EdgeLengthRuleMinAngle = 20.0;
  /// Test hook: accept operations that do not raise the worst quality they touch (only those
  /// that keep every element positive; the mean-quality sweeps drop their floor on the worst
  /// element). Always false in use.
  bool AcceptWorsening = false;
  /// Optional: called before a vertex move is committed with the vertex and its new position
  /// (AmbientDim values); false refuses the move. The meshing pipeline locates the moved site
  /// on the input mesh here.
  std::function<bool(std::int32_t, const double*)> AcceptMove;
  /// Triangles: edge splits (a vertex at the middle of a bad triangle's longest metric edge)
  /// and edge collapses (removal of an end of its shortest), each followed by smoothing of the
  /// vertex left and flips around it, where flips and smoothing alone fail.
  /// Collapses, tets: edge contraction where flips, smoothing and insertion leave a tet below
  /// EdgeLengthRuleMinAngle: a free interior end of one of its edges (shortest metric edge
  /// first) merged into the other end, which stays; kept only if every new tet is positive
  /// (they then tile the old star exactly), no face gets a third tet, no new edge already
  /// exists, and the worst tet of the old star gets better. The removed vertex stays as an
  /// unreferenced point.
  bool Splits = true;
  bool Collapses = true;
  /// Tets: vertex insertion where flips and smoothing fail on a tet below
  /// EdgeLengthRuleMinAngle (the tets that may add out-of-range edges; without KeepEdgeLengths
  /// any tet below TargetAngle): a new vertex at the
  /// tet's metric circumcenter, its centroid or an edge midpoint, the cavity of the tets whose
  /// metric circumspheres contain it (never across the boundary) joined to it, the vertex then
  /// smoothed; kept only if the worst tet of the cavity gets better. The new vertex's metric
  /// comes from PlacePoint (else the mean square root of the tet's vertices) and AddPoint must
  /// accept it.
  bool Insertions = true;
  int MaxInsertionCavity = 48; ///< tets: the most tets one insertion replaces
  /// Tets: a tet below EdgeLengthRuleMinAngle with two boundary faces (a fin or a flat sliver
  /// on the boundary: the final mesh's boundary is sharper there than any smooth domain) is
  /// removed where flips, moves and insertion fail, if its two other faces become a manifold
  /// boundary and no vertex is left without a tet; the volume changes by the tet's. So is an
  /// ear with three boundary faces whose apex is in other tets too (a pinched boundary: the
  /// ear touches the rest only at the apex), its fourth face becoming boundary.
  bool PeelBoundaryTets = true;
  /// Tets: the most volume those removals may take in all, as a fraction of the mesh's volume.
  double BoundaryPeelVolumeBudget = 1e-4;
  /// Surfaces: an edge is flipped only where its two triangles meet at most at this dihedral
  /// angle (degrees), so that the flip moves the surface by a second-order amount.
  double SurfaceFlipMaxDihedral = 20.0;
  /// Surfaces: a collapse must leave the removed vertex within this fraction of the collapsed
  /// edge's length from the triangles that replace its star (flat: 0; a thin tube: large).
  double SurfaceCollapseMaxDeviation = 0.05;
  /// Triangles and tets: places a trial position x (3 values, z = 0 in 2D) of a vertex near
  /// vertex `near` on the domain: writes the point (surfaces: on the input surface; tets: x), the
  /// domain's unit normal there (tets: unused) and the metric there (6 packed values). False: x
  /// is outside the domain. Tets use it for inserted vertices only. Needed
  /// for surfaces (without it they are left unchanged, Supported false); in 2D without it,
  /// positions are taken as given and a moved vertex keeps its metric, a new one gets the mean
  /// square root of its edge's ends.
  std::function<
    bool(std::int32_t near, const double* x, double* placed, double* normal, double* metric)>
    PlacePoint;
  /// Surfaces: puts a trial position x (3 values) of a FeatureLinePoint vertex v on the input's
  /// feature line it lies on (the same line, near its current position), writing the point and
  /// the line's unit tangent there; false when there is none. With it those vertices slide along
  /// their lines in the smoothing (flips, collapses and splits still treat them as fixed, and
  /// never remove an edge between two fixed vertices). Empty: they stay.
  std::function<bool(std::int32_t v, const double* x, double* placed, double* tangent)>
    ProjectToFeatureLine;
  /// Triangles and tets: called when a new vertex is committed (its id is the point count before
  /// it), with a known vertex near it (as PlacePoint's) and its position; false refuses the
  /// operation.
  std::function<bool(std::int32_t id, std::int32_t near, const double* x)> AddPoint;
};

/// Counts of ImproveMesh.
struct MeshImprovementResult
{
  bool Supported = true;      ///< false for surface triangles without PlacePoint: left unchanged
  double WorstBefore = 0.0;   ///< smallest element quality angle before, degrees (< 0: inverted)
  double WorstAfter = 0.0;    ///< the same after
  std::size_t NumFlips23 = 0; ///< tets: 2-3 flips
  std::size_t NumEdgeRemovals = 0; ///< tets: edge removals (3-2 flips included)
  std::size_t NumFlips22 = 0;      ///< triangles: edge flips
  std::size_t NumSmoothed = 0;     ///< accepted vertex moves (the mean-quality sweeps' included)
  std::size_t NumMeanSmoothed = 0; ///< of those, moves of the mean-quality sweeps
  std::size_t NumBoundaryEdgeRemovals = 0; ///< tets: of those, on planar boundary patches
  std::size_t NumBoundarySmoothed = 0; ///< tets: moves of boundary vertices (planar or curved)
  std::size_t NumCreaseSmoothed = 0;   ///< tets: of those, moves along straight creases
  /// Tets: total |volume change| of the curved-boundary operations and the boundary peels, as a
  /// fraction of the volume
  double BoundaryVolumeChange = 0.0;
  std::size_t NumSplits = 0;       ///< triangles: edge splits (new vertices appended)
  std::size_t NumCollapses = 0; ///< edge collapses / tet contractions (removed vertex unused)
  std::size_t NumInsertions = 0;   ///< tets: inserted vertices (new points appended)
  std::size_t NumBoundaryPeels = 0; ///< tets: boundary tets removed (PeelBoundaryTets)
  std::size_t NumBoundarySnaps = 0; ///< tets: vertices moved onto the boundary (SnapToBoundary)
  int Passes = 0;
  std::vector<std::uint8_t> Moved; ///< per point (new ones included), 1 where it changed
};

/**
 * Quality of one simplex in the metric: the vertices (AmbientDim = SimplexDim values each) are
 * mapped by A = (sum_i S_i) / (k+1), S_i the symmetric square roots of the vertex metrics (as in
 * the §5.2 evaluation), and the result is the smallest sine of its angles (triangles) or of its
 * dihedral angles (tets), with the sign of its volume: 1 (triangle) / 0.943 (tet) when regular,
 * near 0 for a sliver, a needle or a cap, negative when inverted. `sqrtMetrics` holds k+1
 * row-major dim x dim matrices.
 */
double MetricSimplexQuality(int simplexDim,
  const double* const* points,
  const double* const* sqrtMetrics);

/**
 * Improves `mesh` (tets in 3D, triangles in 2D or on a surface) in place against `metric` (one per
 * point, the MetricField order): repeatedly, for each element below TargetAngle, the best of edge
 * removal (n <= MaxEdgeRemovalRing tets around an edge, the optimal triangulation of its ring by
 * dynamic programming), 2-3 flips (tets), 2-2 flips (triangles) and moves of its interior vertices
 * (steepest ascent of the worst incident element with a line search), then for triangles edge
 * collapses and splits and for tets vertex insertion, edge contraction and the boundary peel, is applied when it
 * raises the worst quality among the elements it touches. Nothing inverts: an element's quality
 * must stay positive. The boundary and the domain are preserved exactly, except by the tets'
 * curved-boundary operations and peels within their volume budgets: boundary faces (edges) are
 * never flipped, vertices on them, vertices of faces shared by more than two elements, and those
 * flagged in `fixedPoints` (nullptr: none; see FeatureLinePoint) never move (tets: except as
 * PlanarBoundary and StraightCreases say). Vertex metrics stay those given (a move
 * is small against the metric's variation) unless PlacePoint gives them. Unreferenced points are
 * untouched. The cell count may change; the point count only grows by splits and insertions (new
 * points are appended, interior and free; a collapsed or contracted vertex stays as an
 * unreferenced point).
 * Surface triangles need PlacePoint: a triangle's orientation is that of the sum of its vertices'
 * normals, and no operation may flip one. Throws InputError on wrong sizes, bad ids or non-finite
 * values.
 */
MeshImprovementResult ImproveMesh(SimplexMesh& mesh,
  const MetricField& metric,
  const std::vector<std::uint8_t>* fixedPoints,
  const MeshImprovementOptions& options = MeshImprovementOptions());

} // namespace av

#endif
