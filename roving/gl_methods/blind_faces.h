// Internal: the faces of TEST a whole-model view cannot draw, so that a view never resolves a
// sample whose normal line may meet one of them before the depth the view shows (issue 79):
// faces without area (a segment or a point, which rasterise to nothing from any side), and faces
// edge-on to the view's direction (a line in its image). Face normals are binned on a cube map
// once; a view then tests only the faces whose bin its great circle of edge-on normals crosses.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

class BlindFaces {
 public:
  // Edge-on within this angle (radians): the face's image is narrower than 1e-6 of its width,
  // far below a pixel at any resolution --views allows.
  static constexpr double kEdgeOn = 1e-6;

  explicit BlindFaces(const TriangleMesh& test);

  // The faces a view along `direction` (either way) cannot draw, in increasing order.
  std::vector<std::uint32_t> for_view(const Vec3& direction) const;

 private:
  static constexpr int kSide = 32;  // bins along a cube face's side
  const TriangleMesh& test_;
  std::vector<std::uint32_t> degenerate_;
  std::vector<std::uint32_t> offsets_, faces_;  // bin b holds faces_[offsets_[b] .. offsets_[b + 1])
};

}  // namespace roving
