// Uniform subdivision for the scaling benchmark: every triangle split into n^2 by an n x n
// barycentric grid, the points on shared edges and corners shared (the result is as watertight
// as the input), positions on the original flat triangles.
#pragma once

#include "roving/core/triangle_mesh.h"

namespace roving {

TriangleMesh split_triangles(const TriangleMesh& mesh, int n);

}  // namespace roving
