// The benchmark's units (DESIGN.md "Units"): M_R scaled so that its bounding box's longest side
// is 128, the paper's dense voxel grid then being 1 unit; M_C takes the same transform.
#pragma once

#include "roving/core/triangle_mesh.h"

namespace roving {

struct Normalisation {
  Vec3 origin = Vec3::Zero();  // p -> scale * (p - origin)
  double scale = 1;
};

// The transform that puts `reference`'s box at the origin corner with longest side `longest_side`.
Normalisation normalisation_of(const TriangleMesh& reference, double longest_side = 128.0);

inline TriangleMesh apply(const Normalisation& n, const TriangleMesh& mesh) {
  return mesh.transformed(n.origin, n.scale);
}

inline TriangleMesh normalised(const TriangleMesh& mesh, double longest_side = 128.0) {
  return apply(normalisation_of(mesh, longest_side), mesh);
}

}  // namespace roving
