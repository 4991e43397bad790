// The kinds of test model every method must measure accurately against a reference: the
// cooperative method's error bound is checked on each (gl-accuracy, gl_methods_test).
#pragma once

#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct TestVariant {
  std::string name;
  TriangleMesh mesh;
};

// `reference` decimated to 25% and to 5% of its triangles (quadric), moved along its normals by
// 1% of its diagonal (a smooth field), and voxelised (thin, 64 voxels along its longest side).
std::vector<TestVariant> accuracy_variants(const TriangleMesh& reference);

}  // namespace roving
