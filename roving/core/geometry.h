// Small exact-arithmetic-free geometric kernels shared by the references and baselines.
#pragma once

#include <cstdint>

#include "roving/core/triangle_mesh.h"

namespace roving {

// The closest point to `p` on the closed triangle (a, b, c) with its barycentric weights (of a, b,
// c; non-negative, summing to 1), for what is interpolated over the triangle there (colour):
// Ericson, "Real-Time Collision Detection", section 5.1.5. Works for degenerate triangles (a point
// of the segment or the vertex), equal corners included. Inline: Embree's closest-point callback calls it ~13 times a
// query, and inlining saved 3% of the query time.
struct TrianglePoint {
  Vec3 point;
  Vec3 weights;
};

inline TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the vertices, then the edges, then the interior.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, Vec3(1, 0, 0)};

  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, Vec3(0, 1, 0)};

  const double vc = d1 * d4 - d3 * d2;
  // Each edge's test asks for a positive length too (d1 - d3 is |ab|^2): a triangle with two equal
  // corners would otherwise take 0 / 0 here, a NaN point, and a NaN distance stops a BVH's search.
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, Vec3(1 - v, v, 0)};
  }

  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, Vec3(0, 0, 1)};

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {  // |ac|^2 > 0
    const double w = d2 / (d2 - d6);
    return {a + w * ac, Vec3(1 - w, 0, w)};
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {  // |bc|^2 > 0
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), Vec3(0, 1 - w, w)};
  }

  const double denominator = va + vb + vc;
  if (!(denominator > 0)) {
    // Degenerate triangle that fell through the edge tests (collinear corners): nearest corner.
    const double da = (p - a).squaredNorm(), db = (p - b).squaredNorm(), dc = (p - c).squaredNorm();
    if (da <= db && da <= dc) return {a, Vec3(1, 0, 0)};
    return db <= dc ? TrianglePoint{b, Vec3(0, 1, 0)} : TrianglePoint{c, Vec3(0, 0, 1)};
  }
  const double v = vb / denominator, w = vc / denominator;
  return {a + v * ab + w * ac, Vec3(1 - v - w, v, w)};
}

// The point alone.
inline Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return closest_on_triangle(p, a, b, c).point;
}

// Signed distance for closest-point measures: |c - x| with the sign of (c - x) . n, so that it is
// positive where the test surface lies outside the reference along its normal, as with the
// paper's d = h - t, and defined even where c lies on an edge or a vertex.
inline double signed_offset(const Vec3& x, const Vec3& n, const Vec3& c) {
  const Vec3 v = c - x;
  const double length = v.norm();
  return v.dot(n) < 0 ? -length : length;
}

// The Morton (Z-order) code of `p`'s cell in a 1024^3 grid over `box`: points close in space are
// mostly close in this order (triangle clusters; the benchmark's coherent-query study).
std::uint64_t morton_code(const Vec3& p, const BoundingBox& box);

}  // namespace roving
