// Faces a whole-model view cannot draw (blind_faces.h).
#include "blind_faces.h"

#include <algorithm>
#include <cmath>

namespace roving {
namespace {

// A unit direction's bin on the cube map: its largest axis and that axis's sign pick the cube
// face, the other two coordinates over it the cell.
std::uint32_t bin_of(const Vec3& n, int side) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const int sign = n[axis] < 0;
  const double scale = 1 / std::abs(n[axis]);
  const auto cell = [&](int other) {
    return std::clamp(static_cast<int>(std::floor((n[other] * scale + 1) * 0.5 * side)), 0, side - 1);
  };
  return static_cast<std::uint32_t>(((axis * 2 + sign) * side + cell((axis + 1) % 3)) * side + cell((axis + 2) % 3));
}

}  // namespace

BlindFaces::BlindFaces(const TriangleMesh& test) : test_(test) {
  const std::size_t bins = std::size_t(6) * kSide * kSide;
  std::vector<std::uint32_t> bin(test.triangle_count());
  offsets_.assign(bins + 1, 0);
  for (std::size_t f = 0; f < test.triangle_count(); ++f) {
    const Vec3 n = test.face_normal(f);
    if (n.isZero(0)) {
      degenerate_.push_back(static_cast<std::uint32_t>(f));
      bin[f] = static_cast<std::uint32_t>(bins);
      continue;
    }
    bin[f] = bin_of(n, kSide);
    ++offsets_[bin[f] + 1];
  }
  for (std::size_t b = 1; b <= bins; ++b) offsets_[b] += offsets_[b - 1];
  faces_.resize(offsets_.back());
  std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t f = 0; f < bin.size(); ++f) {
    if (bin[f] < bins) faces_[fill[bin[f]]++] = static_cast<std::uint32_t>(f);
  }
}

std::vector<std::uint32_t> BlindFaces::for_view(const Vec3& direction) const {
  std::vector<std::uint32_t> blind = degenerate_;
  const Vec3 w = direction.normalized();
  // A cell's points p (on the cube, |p| <= sqrt 3) hold the normals p / |p|; p . w is linear over
  // the cell, so where it has one sign at the four corners and clears sqrt(3) kEdgeOn there, no
  // normal of the cell is edge-on.
  const double reach = std::sqrt(3.0) * kEdgeOn * (1 + 1e-9) + 1e-15;
  double corner[kSide + 1][kSide + 1];
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = 0; sign < 2; ++sign) {
      for (int i = 0; i <= kSide; ++i) {
        for (int j = 0; j <= kSide; ++j) {
          Vec3 p;
          p[axis] = sign ? -1.0 : 1.0;
          p[(axis + 1) % 3] = -1 + 2.0 * i / kSide;
          p[(axis + 2) % 3] = -1 + 2.0 * j / kSide;
          corner[i][j] = p.dot(w);
        }
      }
      for (int i = 0; i < kSide; ++i) {
        for (int j = 0; j < kSide; ++j) {
          const double c[4] = {corner[i][j], corner[i + 1][j], corner[i][j + 1], corner[i + 1][j + 1]};
          const double low = *std::min_element(c, c + 4), high = *std::max_element(c, c + 4);
          if (low > reach || high < -reach) continue;  // one sign, clear: nothing edge-on here
          const std::size_t b = (std::size_t(axis * 2 + sign) * kSide + i) * kSide + j;
          for (std::uint32_t k = offsets_[b]; k < offsets_[b + 1]; ++k) {
            const std::uint32_t f = faces_[k];
            if (std::abs(test_.face_normal(f).dot(w)) <= kEdgeOn) blind.push_back(f);
          }
        }
      }
    }
  }
  std::sort(blind.begin(), blind.end());
  return blind;
}

}  // namespace roving
