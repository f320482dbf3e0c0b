// SPDX-License-Identifier: BSD-3-Clause
// SameDiagram: two restricted Voronoi diagrams compared field by field, exactly (the update and
// fast-path tests check that a shortcut gives the full computation's output bit for bit).
#ifndef av_VoronoiDiagramCompare_h
#define av_VoronoiDiagramCompare_h

#include "RestrictedVoronoi.h"

#include <iostream>
#include <string>
#include <vector>

namespace av_test
{

template <class T>
inline bool Same(const std::vector<T>& a, const std::vector<T>& b, const std::string& what)
{
  if (a.size() != b.size())
  {
    std::cerr << what << ": sizes " << a.size() << " vs " << b.size() << "\n";
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i]))
    {
      std::cerr << what << ": first difference at " << i << "\n";
      return false;
    }
  return true;
}

// Every field of the two diagrams, exactly.
inline bool SameDiagram(const av::RestrictedVoronoiDiagram& u, const av::RestrictedVoronoiDiagram& f,
  const std::string& name)
{
  bool ok = u.SimplexDim == f.SimplexDim && u.AmbientDim == f.AmbientDim && u.Dim == f.Dim &&
    u.NumSites == f.NumSites;
  ok = Same(u.PieceSite, f.PieceSite, name + " PieceSite") && ok;
  ok = Same(u.PieceElement, f.PieceElement, name + " PieceElement") && ok;
  ok = Same(u.PieceMeasure, f.PieceMeasure, name + " PieceMeasure") && ok;
  ok = Same(u.PieceEmbeddedMeasure, f.PieceEmbeddedMeasure, name + " PieceEmbeddedMeasure") && ok;
  ok = Same(u.PieceVertexOffsets, f.PieceVertexOffsets, name + " PieceVertexOffsets") && ok;
  ok = Same(u.PieceFaceOffsets, f.PieceFaceOffsets, name + " PieceFaceOffsets") && ok;
  ok = Same(u.Points, f.Points, name + " Points") && ok;
  ok = Same(u.EmbeddedPoints, f.EmbeddedPoints, name + " EmbeddedPoints") && ok;
  ok = Same(u.VertexPlanes, f.VertexPlanes, name + " VertexPlanes") && ok;
  ok = Same(u.FaceOffsets, f.FaceOffsets, name + " FaceOffsets") && ok;
  ok = Same(u.FaceVertices, f.FaceVertices, name + " FaceVertices") && ok;
  ok = Same(u.FaceKind, f.FaceKind, name + " FaceKind") && ok;
  ok = Same(u.FaceNeighbor, f.FaceNeighbor, name + " FaceNeighbor") && ok;
  ok = Same(u.SiteMeasure, f.SiteMeasure, name + " SiteMeasure") && ok;
  ok = Same(u.SiteEmbeddedMeasure, f.SiteEmbeddedMeasure, name + " SiteEmbeddedMeasure") && ok;
  ok = Same(u.VoronoiVertexSites, f.VoronoiVertexSites, name + " VoronoiVertexSites") && ok;
  ok = Same(u.VoronoiVertexElement, f.VoronoiVertexElement, name + " VoronoiVertexElement") && ok;
  ok = Same(u.BoundaryDualFaces, f.BoundaryDualFaces, name + " BoundaryDualFaces") && ok;
  ok = Same(u.ElementPieceOffsets, f.ElementPieceOffsets, name + " ElementPieceOffsets") && ok;
  ok = Same(u.ElementVoronoiVertexOffsets, f.ElementVoronoiVertexOffsets,
         name + " ElementVoronoiVertexOffsets") && ok;
  ok = Same(u.ElementBoundaryDualFaceOffsets, f.ElementBoundaryDualFaceOffsets,
         name + " ElementBoundaryDualFaceOffsets") && ok;
  ok = Same(u.ElementNearestSite, f.ElementNearestSite, name + " ElementNearestSite") && ok;
  ok = Same(u.ElementBoundaryFacets, f.ElementBoundaryFacets, name + " ElementBoundaryFacets") && ok;
  ok = Same(u.ElementEmptyVisit, f.ElementEmptyVisit, name + " ElementEmptyVisit") && ok;
  ok = Same(u.PieceSecurityRadius2, f.PieceSecurityRadius2, name + " PieceSecurityRadius2") && ok;
  ok = Same(u.PieceLastCutDistance, f.PieceLastCutDistance, name + " PieceLastCutDistance") && ok;
  return ok;
}

} // namespace av_test

#endif
