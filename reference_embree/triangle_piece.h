// Internal: a piece of one of A's triangles with bounds on the distance to B over it, and its
// split in four; shared by the certified bounds (certified_hausdorff.cpp, certified_area_within.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>

#include "closest_points.h"

namespace roving {

// A piece of one of A's triangles, with its corners' distances to B and the candidate triangles of
// B its upper bound was taken over.
struct Piece {
  std::array<Vec3, 3> corner;
  std::array<double, 3> distance;
  std::array<std::uint32_t, 6> candidates;
  int candidate_count = 0;
  int depth = 0;  // splits from A's triangle
  // Its area: a fourth of its parent's, exactly (midpoints split a triangle in four equal parts),
  // never recomputed from its corners, which the midpoints' rounding moves (a sliver's area is
  // all rounding).
  double area = 0;
  double upper = 0;
  bool operator<(const Piece& other) const { return upper < other.upper; }  // a max-heap by upper bound
};

// The upper bound over the piece's candidates: the distance to one triangle of B is convex, so over
// the piece it peaks at a corner, and the distance to B is at most that (certified_hausdorff.h).
inline void bound(Piece& piece, const ClosestPoints& b) {
  piece.upper = std::numeric_limits<double>::infinity();
  for (int c = 0; c < piece.candidate_count; ++c) {
    double worst = 0;
    for (const Vec3& x : piece.corner) worst = std::max(worst, b.distance_to(x, piece.candidates[c]));
    piece.upper = std::min(piece.upper, worst);
  }
}

// The candidates of a piece: its corners' closest triangles, then its parent's, without repeats.
inline void add_candidate(Piece& piece, std::uint32_t t) {
  for (int c = 0; c < piece.candidate_count; ++c) {
    if (piece.candidates[c] == t) return;
  }
  if (piece.candidate_count < static_cast<int>(piece.candidates.size())) piece.candidates[piece.candidate_count++] = t;
}

// The four children of `parent` by its edges' midpoints (corners 0, 1, 2 and midpoints m0 (0-1),
// m1 (1-2), m2 (2-0)), each bounded; `midpoints` gets the midpoints and their closest points on B.
inline std::array<Piece, 4> split(const Piece& parent, const ClosestPoints& b,
                                  std::array<std::pair<Vec3, ClosestPoints::Found>, 3>& midpoints) {
  std::array<Vec3, 3> m;
  std::array<ClosestPoints::Found, 3> f;
  for (int i = 0; i < 3; ++i) {
    m[i] = 0.5 * (parent.corner[i] + parent.corner[(i + 1) % 3]);
    f[i] = b.query(m[i]);
    midpoints[i] = {m[i], f[i]};
  }
  const std::array<std::array<int, 3>, 4> shape = {{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
  std::array<Piece, 4> children;
  for (int c = 0; c < 4; ++c) {
    Piece& child = children[c];
    child.depth = parent.depth + 1;
    child.area = parent.area / 4;
    for (int i = 0; i < 3; ++i) {
      const int at = shape[c][i];
      child.corner[i] = at < 3 ? parent.corner[at] : m[at - 3];
      child.distance[i] = at < 3 ? parent.distance[at] : f[at - 3].distance;
      if (at >= 3) add_candidate(child, f[at - 3].triangle);
    }
    for (int p = 0; p < parent.candidate_count; ++p) add_candidate(child, parent.candidates[p]);
    bound(child, b);
  }
  return children;
}

}  // namespace roving
