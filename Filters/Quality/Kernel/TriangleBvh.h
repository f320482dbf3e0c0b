// SPDX-License-Identifier: BSD-3-Clause
// TriangleBvh: an axis-aligned bounding-box tree over the triangles of a 3D surface, for the
// fidelity measures (closest point, overlapping pairs). VTK-free.
#ifndef av_TriangleBvh_h
#define av_TriangleBvh_h

#include "SimplexMesh.h"

#include <Eigen/Geometry> // AlignedBox3d

#include <cstdint>
#include <vector>

namespace av
{

/// Closest point of triangle (a, b, c) to p (Ericson's region test), exact in the plane case.
Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p,
  const Eigen::Vector3d& a,
  const Eigen::Vector3d& b,
  const Eigen::Vector3d& c);

/**
 * Bounding-volume hierarchy of a triangle surface (AmbientDim 3, SimplexDim 2): a binary tree,
 * split at the median centroid along the box's longest axis, at most 4 triangles per leaf. The
 * tree keeps a reference to `surface`, which must outlive it. Queries are const and may run
 * from several threads at once.
 */
class TriangleBvh
{
public:
  /// Throws InputError for a mesh that is not a triangle surface in 3D or is empty.
  explicit TriangleBvh(const SimplexMesh& surface);

  /// Squared distance from p to the surface and the closest triangle (branch and bound).
  double ClosestDistance2(const Eigen::Vector3d& p, std::int32_t* triangle = nullptr) const;

  /// Calls visit(t) for every triangle t whose box overlaps `box`.
  template <class Visit>
  void ForEachOverlapping(const Eigen::AlignedBox3d& box, Visit visit) const
  {
    std::int32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& n = this->Nodes[stack[--top]];
      if (!n.Box.intersects(box))
        continue;
      if (n.Count > 0)
      {
        for (std::int32_t k = n.First; k < n.First + n.Count; ++k)
        {
          if (this->Boxes[this->Order[k]].intersects(box))
            visit(this->Order[k]);
        }
      }
      else
      {
        stack[top++] = n.First;
        stack[top++] = n.First + 1;
      }
    }
  }

  /// Bounding box of triangle t.
  const Eigen::AlignedBox3d& TriangleBox(std::int32_t t) const { return this->Boxes[t]; }

private:
  struct Node
  {
    Eigen::AlignedBox3d Box;
    std::int32_t First = 0; ///< leaf: first index into Order; inner: left child (right = +1)
    std::int32_t Count = 0; ///< leaf: triangle count; inner: 0
  };
  void Build(std::int32_t node, std::int32_t begin, std::int32_t end, int depth);

  const SimplexMesh& Surface;
  std::vector<Eigen::AlignedBox3d> Boxes;
  std::vector<Eigen::Vector3d> Centroids;
  std::vector<std::int32_t> Order;
  std::vector<Node> Nodes;
};

} // namespace av

#endif
