#pragma once
// Where on a tissue mesh a point is (docs/mesh.md): the closest point of the surface to any point
// in space, as a triangle and barycentric coordinates, and its texture coordinate — how the
// stylus' contact becomes a texel, and a cut's wound follows the surface.
//
// The closest point comes from a small bounding-volume hierarchy of our own (median splits along the
// longest axis, at most four triangles a leaf): it serves meshes of thousands to millions of
// triangles, gives the same answer on every machine (a tie goes to the lowest triangle index,
// whatever the traversal), and needs no library beside Eigen. Embree (Debian's libembree-dev) is
// built for casting rays, which we do not; nanoflann answers nearest vertices, not nearest points
// of triangles.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/mesh/tissue_mesh.h"

namespace bleedsim {

struct SurfacePoint {
  int triangle = -1;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // weights of the triangle's corners
  Eigen::Vector3d point = Eigen::Vector3d::Zero();        // mm
  double distance_mm = 0.0;
};

// Where a segment passes through the surface: the segment's parameter (0 at its start, 1 at its end)
// and the point of the triangle it passes through (distance_mm 0).
struct SegmentCrossing {
  double t = 0.0;
  SurfacePoint at;
};

class MeshSurface {
 public:
  explicit MeshSurface(TissueMesh mesh);

  // The surface's point nearest to p; of points equally near, the one on the lowest triangle.
  SurfacePoint closest(const Eigen::Vector3d& p) const;
  // The texture coordinate at a point of the surface: its triangle's uvs weighted by its barycentric
  // coordinates.
  Eigen::Vector2d uv(const SurfacePoint& at) const;
  // Every triangle the segment from a to b passes through, nearest a first (ties by triangle
  // index). A segment that meets a triangle only edge-on (lying in its plane) does not pass through
  // it. A crossing on an edge or corner within 1e-12 of the barycentric range counts for each
  // triangle there, so that no crossing slips between two triangles by rounding; likewise a segment
  // that starts or ends on a triangle (within 1e-9 of its length) passes through it.
  std::vector<SegmentCrossing> crossings(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

  const TissueMesh& mesh() const { return mesh_; }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0, count = 0;  // a leaf's triangles: order_[first, first + count)
    int left = -1, right = -1; // an inner node's children
  };
  int build(int first, int count);

  TissueMesh mesh_;
  std::vector<int> order_;  // triangle indices, grouped by leaf
  std::vector<Node> nodes_;
};

// The point of triangle abc nearest to p, as barycentric weights (Ericson, Real-Time Collision
// Detection, 5.1.5: by the Voronoi regions of the corners, edges and face).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c);

}  // namespace bleedsim
