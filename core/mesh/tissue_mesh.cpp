#include "core/mesh/tissue_mesh.h"

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

}  // namespace bleedsim
