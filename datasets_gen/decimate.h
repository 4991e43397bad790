// Quadric-error decimation (Garland and Heckbert 1997) through OpenMesh's decimater.
#pragma once

#include <cstddef>

#include "roving/core/triangle_mesh.h"

namespace roving {

// Collapses edges of `mesh` in order of quadric error until it has exactly `target_triangles`.
// An interior collapse removes two triangles and a boundary one removes one, so an odd gap is
// closed by letting the last step be a boundary collapse; throws roving::Error if the exact
// count cannot be reached (a closed mesh with an odd gap) or the mesh is not manifold.
TriangleMesh decimate_quadric(const TriangleMesh& mesh, std::size_t target_triangles);

}  // namespace roving
