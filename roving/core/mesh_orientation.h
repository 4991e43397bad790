// Whether a mesh is closed and consistently oriented, and its signed volume: a closed mesh
// with negative volume is inside out (its normals point in), which flips every signed d.
#pragma once

#include "roving/core/triangle_mesh.h"

namespace roving {

struct Orientation {
  // Every directed edge a->b is matched by one b->a: closed, and each edge's two faces agree.
  bool closed_and_consistent = false;
  double signed_volume = 0;  // meaningful only when closed_and_consistent
};

Orientation orientation(const TriangleMesh& mesh);

}  // namespace roving
