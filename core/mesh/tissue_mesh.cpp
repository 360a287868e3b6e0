#include "core/mesh/tissue_mesh.h"

#include <cmath>

#include <Eigen/Geometry>

namespace bleedsim {

double TissueMesh::area_mm2() const {
  double sum = 0.0;
  for (const Triangle& t : triangles)
    sum += 0.5 * (positions[t.corner[1]] - positions[t.corner[0]])
                     .cross(positions[t.corner[2]] - positions[t.corner[0]])
                     .norm();
  return sum;
}

TissueMesh placed(TissueMesh mesh, const MeshPlacement& at) {
  const auto turn = [](double degrees, const Eigen::Vector3d& axis) {
    return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis).toRotationMatrix();
  };
  const Eigen::Matrix3d r = turn(at.rotation_deg.z(), Eigen::Vector3d::UnitZ()) *
                            turn(at.rotation_deg.y(), Eigen::Vector3d::UnitY()) *
                            turn(at.rotation_deg.x(), Eigen::Vector3d::UnitX());
  for (Eigen::Vector3d& p : mesh.positions) p = at.position_mm + at.scale * (r * p);
  return mesh;
}

}  // namespace bleedsim
