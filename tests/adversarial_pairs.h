// Adversarial pairs for the exact oracle (exact_oracle_test.cpp and the fuzz target): small TEST
// meshes made of the triangles floating point decides worst (two or three equal corners, collinear
// corners, needles and caps down to an aspect of 1e-12, slivers, duplicate and opposite-wound
// faces, coplanar overlaps, non-manifold edges, T-junctions, unreferenced vertices), moved by
// offsets of 1e6 and scaled by 1e-6 and 1e6, and the sample points to measure from them: at
// TEST's vertices, on its edges, near its faces and around them at every scale.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"

namespace roving::adversarial {

// Reads choices from a byte string (libFuzzer's input) or from a seeded generator alike.
class Choices {
 public:
  explicit Choices(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 1) {}
  Choices(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint64_t next() {
    if (data_) {
      std::uint64_t v = 0;
      for (int i = 0; i < 8; ++i) v = v << 8 | (at_ < size_ ? data_[at_++] : 0);
      return v;
    }
    state_ ^= state_ << 13, state_ ^= state_ >> 7, state_ ^= state_ << 17;  // xorshift64
    return state_;
  }
  int below(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  double unit() { return static_cast<double>(next() >> 11) * 0x1p-53; }    // [0, 1)
  double symmetric() { return 2 * unit() - 1; }                            // [-1, 1)
  Vec3 vector() { return Vec3(symmetric(), symmetric(), symmetric()); }
  bool exhausted() const { return data_ && at_ >= size_; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0, at_ = 0;
  std::uint64_t state_ = 0;
};

// One adversarial triangle of size about 1 near the origin; `kind` says which.
inline std::array<Vec3, 3> triangle(Choices& choose, std::string& kind) {
  const Vec3 a = choose.vector(), c = choose.vector();
  const double aspect = std::pow(10.0, -1 - choose.below(12));  // 1e-1 .. 1e-12
  Vec3 across = (c - a).cross(choose.vector());
  if (across.squaredNorm() == 0) across = Vec3(0, 0, 1);
  across = across.normalized() * (c - a).norm();
  switch (choose.below(9)) {
    case 0: kind = "well-shaped"; return {a, choose.vector(), c};
    case 1: kind = "two equal corners"; return {a, a, c};
    case 2: kind = "three equal corners"; return {a, a, a};
    case 3: {
      kind = "collinear corners (exact)";
      const Vec3 a2 = (4 * a).array().round().matrix() / 4, c2 = (4 * c).array().round().matrix() / 4 + Vec3(0.5, 0, 0);
      return {a2, a2 + 0.25 * (c2 - a2), c2};
    }
    case 4: kind = "collinear corners (rounded)"; return {a, a + (1.0 / 3) * (c - a), c};
    case 5: kind = "needle"; return {a, a + aspect * across, c};
    case 6: kind = "cap"; return {a, 0.5 * (a + c) + aspect * across, c};
    case 7: kind = "sliver"; return {a, a + choose.unit() * (c - a) + aspect * across, c};
    default: kind = "cap near a corner"; return {a, a + 1e-3 * (c - a) + aspect * across, c};
  }
}

struct Pair {
  TriangleMesh test;
  SampleSet samples;  // positions and unit normals; weights 1
  std::string what;
};

// A TEST of one to four adversarial triangles (with duplicates, opposite windings, a coplanar
// overlap, a T-junction, an unreferenced vertex, as chosen), moved and scaled, and `count` samples.
inline Pair pair(Choices& choose, int count) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  std::string what;
  const int faces = 1 + choose.below(4);
  for (int f = 0; f < faces; ++f) {
    std::string kind;
    const auto t = triangle(choose, kind);
    const int base = static_cast<int>(positions.size());
    positions.insert(positions.end(), t.begin(), t.end());
    triangles.push_back({base, base + 1, base + 2});
    what += (f ? ", " : "") + kind;
    switch (choose.below(6)) {
      case 0: triangles.push_back({base, base + 1, base + 2}); what += " (duplicated)"; break;
      case 1: triangles.push_back({base, base + 2, base + 1}); what += " (and opposite-wound)"; break;
      case 2: {  // coplanar overlap: a piece of the same plane, shifted within it
        const Vec3 shift = 0.3 * (t[1] - t[0]) + 0.2 * (t[2] - t[0]);
        positions.insert(positions.end(), {t[0] + shift, t[1] + shift, t[2] + shift});
        triangles.push_back({base + 3, base + 4, base + 5});
        what += " (and a coplanar overlap)";
        break;
      }
      case 3: {  // T-junction: two triangles meeting the first edge's midpoint
        positions.push_back(0.5 * (t[0] + t[1]));
        positions.push_back(t[0] + (t[0] - t[2]));
        triangles.push_back({base, base + 3, base + 4});
        triangles.push_back({base + 3, base + 1, base + 4});
        what += " (and a T-junction)";
        break;
      }
      case 4: {  // non-manifold edge: a third face on the first edge
        positions.push_back(t[0] + (t[1] - t[0]).cross(t[2] - t[0]));
        triangles.push_back({base, base + 1, base + 3});
        what += " (and a non-manifold edge)";
        break;
      }
      default: positions.push_back(choose.vector() * 3); what += " (and an unreferenced vertex)"; break;
    }
  }
  // Where the model lies: offsets of 1e6 and scales of 1e-6 and 1e6 lose or stretch the digits.
  double scale = 1;
  Vec3 offset = Vec3::Zero();
  switch (choose.below(5)) {
    case 0: scale = 1e-6; what += "; scaled by 1e-6"; break;
    case 1: scale = 1e6; what += "; scaled by 1e6"; break;
    case 2: offset = Vec3(1e6, -1e6, 0.5e6); what += "; offset by 1e6"; break;
    default: break;
  }
  for (Vec3& p : positions) p = p * scale + offset;

  Pair made{TriangleMesh(positions, triangles), {}, what};
  SampleSet& s = made.samples;
  for (int k = 0; k < count; ++k) {
    const Triangle& t = triangles[choose.below(static_cast<int>(triangles.size()))];
    const Vec3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    Vec3 x;
    const double r = choose.unit(), q = choose.unit();
    switch (choose.below(6)) {
      case 0: x = positions[t[choose.below(3)]]; break;                              // at a vertex
      case 1: x = a + r * (b - a); break;                                             // on an edge
      case 2: x = a + r * (b - a) + q * (1 - r) * (c - a); break;                      // on the face
      case 3: x = (a + b + c) / 3 + scale * std::pow(10.0, -choose.below(10)) * choose.vector(); break;
      case 4: x = a + scale * std::pow(10.0, -choose.below(14)) * choose.vector(); break;  // near a corner
      default: x = offset + scale * 2 * choose.vector(); break;                       // around
    }
    Vec3 n = choose.below(4) == 0 ? (b - a).cross(c - a) : choose.vector();
    if (!(n.squaredNorm() > 0) || !n.allFinite()) n = Vec3(0, 0, 1);
    s.positions.push_back(x);
    s.normals.push_back(n.normalized());
    s.weights.push_back(1);
  }
  return made;
}

}  // namespace roving::adversarial
