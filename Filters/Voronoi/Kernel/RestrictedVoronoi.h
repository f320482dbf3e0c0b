// SPDX-License-Identifier: BSD-3-Clause
// RestrictedVoronoi: the Voronoi diagram of sites in R^Dim restricted to an embedded simplicial
// mesh (paper §4.2). Every element is clipped in its own barycentric coordinates, so the work
// per clip is k-dimensional whatever Dim is.
#ifndef av_RestrictedVoronoi_h
#define av_RestrictedVoronoi_h

#include "MeshTopology.h" // ComputeElementAdjacency, for RestrictedVoronoiOptions
#include "SimplexMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace av
{

/// What the plane carrying a face (3D) or an edge (2D) of a piece is.
enum class RVDFaceKind : std::int8_t
{
  Bisector = 0,       ///< bisector with another site (FaceNeighbor = that site id)
  DomainBoundary = 1, ///< boundary of the input mesh (FaceNeighbor = -1)
  ElementFace = 2     ///< facet shared with another element (FaceNeighbor = that element id)
};

/// Options of ComputeRestrictedVoronoi.
struct RestrictedVoronoiOptions
{
  /// false: only measures and the dual (Voronoi vertex) records, no vertices/faces (saves memory).
  bool ComputeGeometry = true;
  /// Store every vertex in R^Dim as well (EmbeddedPoints); input-space points are always kept.
  /// Off by default: nothing downstream reads them (they are Sum lambda x embedded vertex of
  /// the piece's element), and they are most of the geometry's memory (Dim of AmbientDim +
  /// Dim doubles per vertex).
  bool KeepEmbeddedPoints = false;
  /// Per-site cells: drop internal element faces and sort pieces by site (then by element).
  /// What renders a Voronoi cell with its bisector and boundary faces.
  bool MergeBySite = false;
  /// Nearest neighbors prefetched per site (0: automatic). More are fetched on demand.
  int NumNeighbors = 0;
  /// Clip only elements [ElementBegin, ElementEnd) (ElementEnd < 0: up to the last element)
  /// against all sites: one process's share of a distributed run. The pieces of the range are
  /// exactly those of a full run (same order); SiteMeasure then sums the range only, and
  /// MergeBySite merges only inside the range.
  std::int64_t ElementBegin = 0;
  std::int64_t ElementEnd = -1;
  /// ComputeElementAdjacency(mesh) computed once by a caller that runs several diagrams on
  /// the same mesh (nullptr: computed here; about 20 ms for 240k tets). Must outlive the call.
  const std::vector<std::int32_t>* ElementAdjacency = nullptr;
  /// An element whose K+1 vertices all have the same nearest site n (by a clear margin) lies
  /// in n's convex cell: it is emitted as one whole piece without candidates or clipping.
  /// The output is the same with it off (kept for tests and benchmarks).
  bool WholeElementFastPath = true;
};

/**
 * The restricted Voronoi diagram: one convex piece per (element, site) whose intersection is
 * non-empty. Pieces are polygons for triangle meshes and convex polyhedra for tet meshes.
 *
 * Vertex planes encode the symbolic definition of every vertex: SimplexDim plane labels,
 * label s >= 0 = bisector of the piece's site with site s, label -(a+1) = facet a of the
 * element (the facet opposite local vertex a). A vertex whose labels are all bisectors is a
 * Voronoi vertex inside the domain (dual to a restricted Delaunay simplex).
 *
 * Faces: 3D pieces have polygonal faces (vertex loops, counter-clockwise seen from outside in
 * barycentric coordinates of the element); 2D pieces have edges (2 vertices) and their
 * vertices are stored in loop order, so vertices PieceVertexOffsets[p]..[p+1] are the polygon.
 * Vertex ids in FaceVertices are global (index into Points / EmbeddedPoints).
 */
struct RestrictedVoronoiDiagram
{
  int SimplexDim = 3;
  int AmbientDim = 3;
  int Dim = 8;
  std::size_t NumSites = 0;

  // Per piece.
  std::vector<std::int32_t> PieceSite;
  std::vector<std::int32_t> PieceElement;
  std::vector<double> PieceMeasure;         ///< area / volume in input space
  std::vector<double> PieceEmbeddedMeasure; ///< area / volume in R^Dim
  std::vector<std::int64_t> PieceVertexOffsets; ///< NumPieces + 1 (geometry only)
  std::vector<std::int64_t> PieceFaceOffsets;   ///< NumPieces + 1 (geometry only)

  // Per vertex (geometry only).
  std::vector<double> Points;           ///< NumVertices x AmbientDim, input space
  std::vector<double> EmbeddedPoints;   ///< NumVertices x Dim (if KeepEmbeddedPoints)
  std::vector<std::int32_t> VertexPlanes; ///< NumVertices x SimplexDim, see above

  // Per face (3D) / edge (2D) (geometry only).
  std::vector<std::int64_t> FaceOffsets; ///< NumFaces + 1 into FaceVertices
  std::vector<std::int32_t> FaceVertices;
  std::vector<RVDFaceKind> FaceKind;
  std::vector<std::int32_t> FaceNeighbor;

  // Per site: total measure of its restricted cell.
  std::vector<double> SiteMeasure;
  std::vector<double> SiteEmbeddedMeasure;

  /// Voronoi vertices strictly inside elements: SimplexDim+1 sorted site ids each, and the
  /// element that holds it. The same vertex is listed once per site that sees it.
  std::vector<std::int32_t> VoronoiVertexSites;
  std::vector<std::int32_t> VoronoiVertexElement;
  /// Dual faces that reach the domain boundary: SimplexDim sorted site ids per entry
  /// (the sites of a Voronoi edge / polygon that meets the boundary), possibly repeated.
  std::vector<std::int32_t> BoundaryDualFaces;

  // Per element (what UpdateRestrictedVoronoi needs to splice a new diagram). Filled only for
  // a whole-mesh run (ElementBegin/End at their defaults) without MergeBySite, else empty.
  /// NumElements + 1: pieces of element e are [ElementPieceOffsets[e], [e+1]).
  std::vector<std::int64_t> ElementPieceOffsets;
  /// NumElements + 1, in records: VoronoiVertexElement entries of element e (each record is
  /// SimplexDim+1 entries of VoronoiVertexSites).
  std::vector<std::int64_t> ElementVoronoiVertexOffsets;
  /// NumElements + 1, in records of SimplexDim entries of BoundaryDualFaces.
  std::vector<std::int64_t> ElementBoundaryDualFaceOffsets;
  /// The site nearest to the element's embedded centroid (ties: lowest id): the reference of
  /// the element's candidate sites (a site can only change the element's pieces if it is
  /// closer than this one to some vertex of the element).
  std::vector<std::int32_t> ElementNearestSite;
  /// 1: the element's flood fill visited a site whose piece turned out empty (near-ties).
  std::vector<std::uint8_t> ElementEmptyVisit;
  /// Per piece (same condition): squared security radius (max over the piece's vertices of
  /// the squared embedding distance to its site) and the distance from the element's centroid
  /// of the last site whose bisector cut the piece (-1: none), both rounded up to float. A new
  /// site farther from the centroid than that, and farther than 2 x the radius from the
  /// piece's site, cannot cut the piece while it is being clipped.
  std::vector<float> PieceSecurityRadius2;
  std::vector<float> PieceLastCutDistance;
  /// Bit a set: facet a of the element is on the domain boundary.
  std::vector<std::uint8_t> ElementBoundaryFacets;
  /// Elements clipped by the call that produced this diagram (all of the range for
  /// ComputeRestrictedVoronoi, only the affected ones for UpdateRestrictedVoronoi).
  std::size_t NumRecomputedElements = 0;
  /// Of those, the elements emitted whole by the fast path (WholeElementFastPath).
  std::size_t NumWholeElements = 0;

  std::size_t NumPieces() const { return PieceSite.size(); }
  std::size_t NumVertices() const { return Points.size() / static_cast<std::size_t>(AmbientDim); }
  std::size_t NumFaces() const { return FaceKind.size(); }
};

/**
 * Checks mesh / embedding / sites for ComputeRestrictedVoronoi and throws InputError with an
 * actionable message: wrong sizes, NaN, ids out of range, barycentric weights that do not sum
 * to 1 or are negative, site coordinates that are not the barycentric combination of their
 * cell's embedded vertices (site outside the mesh), degenerate embedded elements, no sites.
 */
void ValidateRestrictedVoronoiInput(const SimplexMesh& mesh, const Embedding& embedding,
  const SiteSet& sites);

/// Throws InputError when even a lower bound of the diagram's memory (one piece per element
/// and per site) exceeds what the process may allocate (MemoryBudget.h).
void RequireRestrictedVoronoiMemory(
  const SimplexMesh& mesh, const Embedding& embedding, std::size_t numSites);

/**
 * Computes the restricted Voronoi diagram of `sites` on the embedded mesh. Exact up to
 * floating-point round-off; every decision about a vertex is made from its symbolic
 * definition (so pieces of one element never disagree), ties are broken by site index
 * (the lower index is taken as closer). Threads with TBB; output order is deterministic
 * (elements in order, pieces in flood-fill order inside an element, or by site with
 * MergeBySite).
 */
RestrictedVoronoiDiagram ComputeRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites,
  const RestrictedVoronoiOptions& options = RestrictedVoronoiOptions());

/**
 * The restricted Voronoi diagram of `sites` from `previous`, the diagram of `previousSites`
 * (same mesh, embedding and options), where `sites` holds the previous sites (some of them
 * possibly moved) followed by new ones. Only the elements whose pieces can change are clipped
 * again, the others are copied: an element keeps its pieces unless a new or moved site (at its
 * new or its old position) is a candidate of the element (not farther than the element's
 * nearest site, ElementNearestSite, from every vertex of the element) that can cut one of
 * its pieces while that piece is clipped (PieceLastCutDistance, PieceSecurityRadius2), or
 * the site of one of its pieces moved. The result equals ComputeRestrictedVoronoi(mesh, embedding,
 * sites, options) field by field (bit-identical: same pieces in the same order, records,
 * measures and sums). With ComputeGeometry, MergeBySite, an element range, many changed sites
 * or a `previous` without the per-element members, it runs the full computation.
 * NumRecomputedElements tells how many elements were clipped. Throws InputError as
 * ComputeRestrictedVoronoi, and when `previous` does not belong to `previousSites` or the
 * sites were not appended to them.
 */
RestrictedVoronoiDiagram UpdateRestrictedVoronoi(const SimplexMesh& mesh,
  const Embedding& embedding, const SiteSet& sites, const RestrictedVoronoiDiagram& previous,
  const SiteSet& previousSites, const RestrictedVoronoiOptions& options = RestrictedVoronoiOptions());

} // namespace av

#endif
