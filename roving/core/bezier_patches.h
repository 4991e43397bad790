// Parametric surfaces: tensor-product Bezier patches (the teapot's `.bpt`).
#pragma once

#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

struct BezierPatch {
  int degree_u = 3, degree_v = 3;
  std::vector<Vec3> control;  // (degree_u + 1) x (degree_v + 1), row i (u) by column j (v)

  const Vec3& at(int i, int j) const { return control[i * (degree_v + 1) + j]; }
};

struct BezierSurface {
  std::vector<BezierPatch> patches;
};

}  // namespace roving
