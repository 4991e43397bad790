// The geometric kernels shared by every method: closest points on triangles (exact in their
// decisions), signed offsets and Morton codes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "roving/core/triangle_mesh.h"

namespace roving {

// The closest point to `p` on the closed triangle (a, b, c) with its barycentric weights (of a, b,
// c; non-negative, summing to 1), for what is interpolated over the triangle there (colour).
//
// Exact in its decisions, whatever the triangle's shape. The fast path is Ericson's ("Real-Time
// Collision Detection", section 5.1.5): Voronoi regions of the vertices, the edges, the interior.
// Each region test it takes is a polynomial of degree 2 or 4 in the corners' differences; it is
// trusted only where its value clears its rounding bound (Higham's gamma_n over the magnitudes of
// the differences), and its point only where the point's own rounding error keeps the distance
// within the kernel's bound. Everything else (a sample on an edge or a vertex, thin needles and
// caps, two or three equal or collinear corners) goes to `closest_on_triangle_exact`, which decides
// in rational arithmetic and treats a degenerate triangle as the segment or point it is. Thin or
// degenerate triangles are what quantised codec output is full of; the fast path takes well over
// 99% of the calls on well-shaped meshes (the benchmark's 10 M pair).
//
// The bound: |distance(p, point) - exact distance| <= closest_point_error_bound(M), where M is the
// largest absolute coordinate of p, a, b and c (tests/exact_oracle_test.cpp checks it against an
// exact rational oracle on adversarial triangles).
struct TrianglePoint {
  Vec3 point;
  Vec3 weights;
};

// 1024 units in the last place of the largest coordinate (1.1e-13 of it): the error of rounding
// the closest point to doubles and of measuring its distance, with room for the fast path's
// accepted error (a plane's distance in double is known to some hundred units).
constexpr double kClosestPointUlps = 1024;
inline double closest_point_error_bound(double largest_coordinate) {
  return kClosestPointUlps * 0x1p-53 * largest_coordinate;
}

// The rational-arithmetic answer (geometry.cpp): exact decisions, the exact point rounded (p at a
// corner first, without rationals: every vertex sample of a model measured against itself).
TrianglePoint closest_on_triangle_exact(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
// Where the fast path cannot decide (geometry.cpp): the nearest of the three edges' points and of
// the projection where it may be inside, kept where a lower bound of the exact distance (the
// plane's) shows it within the kernel's bound, or where the projection is clearly outside; the
// exact answer otherwise. Samples on or near edges and vertices (a model against itself, grids
// that share vertices) end here, without rationals.
TrianglePoint closest_on_triangle_careful(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Inline, and in Ericson's order, computing each test only when the ones before it have not
// answered: Embree's closest-point callback calls it ~13 times a query.
__attribute__((always_inline)) inline TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                                       const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  // Rounding bounds. Each computed difference is within a unit roundoff u of the exact one; a dot
  // of an edge and an offset of p is within gamma_4 * sum |x_i y_i| <= 12.1 u me mp of the exact
  // dot (me: the edges' largest component; mp: the offsets' ap, bp = ap - ab, cp = ap - ac, so at
  // most |ap| + me), bounded here by 16 u me mp; a difference of two dots by 48 u me mp; a degree-4
  // term d_i d_j - d_k d_l by 256 u me^2 mp^2. Each region is taken only where all of its own
  // tests clear their bounds: each is the region's exact condition (Ericson's), so no other test
  // need be decided; where none is taken, closest_on_triangle_careful decides.
  constexpr double u = 0x1p-53;
  const auto largest_of = [](const Vec3& v) {  // not Eigen's reduction, which stays a call here
    return std::max(std::max(std::abs(v.x()), std::abs(v.y())), std::abs(v.z()));
  };
  const double me = std::max(largest_of(ab), largest_of(ac));
  const double mp = largest_of(ap) + me;
  const double e2 = 16 * u * me * mp, e2_difference = 3 * e2, e4 = 256 * u * (me * mp) * (me * mp);

  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 < -e2 && d2 < -e2) return {a, Vec3(1, 0, 0)};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 > e2 && d3 - d4 > e2_difference) return {b, Vec3(0, 1, 0)};

  // What an edge's or the interior's point may add to the distance by its rounding: the kernel's
  // bound over a lower bound of the largest coordinate M (|b - a| <= 2 M), less 8 u M for
  // rounding the point and its distance.
  const auto largest = [&] { return std::max(std::max(largest_of(a), largest_of(p)), me / 2); };
  const auto allowed = [](double m) { return closest_point_error_bound(m) - 8 * u * m; };
  // An edge's point moves along the edge with its parameter's rounding, which changes the distance
  // by at most that move: kept where the move is within what is allowed; otherwise where the
  // distance to it exceeds the distance to the edge's line (exact for the region decided, less its
  // own rounding: 16 u of the offset's length) by less.
  // The move is given as a quotient, so that no division is spent where it is clearly small.
  const auto keep_on_edge = [&](const Vec3& point, double move_numerator, double move_denominator,
                                const Vec3& offset, const Vec3& edge) {
    const double limit = allowed(largest());
    if (move_numerator <= limit * move_denominator) return true;
    const double line = offset.cross(edge).norm() / edge.norm() - 16 * u * offset.norm();
    return (point - p).norm() * (1 + 4 * u) - line <= limit;
  };
  const double vc = d1 * d4 - d3 * d2;
  if (vc < -e4 && d1 > e2 && d3 < -e2) {
    const double length_squared = d1 - d3;  // |ab|^2, within 3 e2
    const double v = std::clamp(d1 / length_squared, 0.0, 1.0);
    const Vec3 point = a + v * ab;
    if (length_squared > 2 * e2_difference &&
        keep_on_edge(point, 1.8 * me * (e2 + v * e2_difference), length_squared - e2_difference, ap, ab))
      return {point, Vec3(1 - v, v, 0)};
    return closest_on_triangle_careful(p, a, b, c);
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 > e2 && d6 - d5 > e2_difference) return {c, Vec3(0, 0, 1)};
  const double vb = d5 * d2 - d1 * d6;
  if (vb < -e4 && d2 > e2 && d6 < -e2) {
    const double length_squared = d2 - d6;  // |ac|^2
    const double w = std::clamp(d2 / length_squared, 0.0, 1.0);
    const Vec3 point = a + w * ac;
    if (length_squared > 2 * e2_difference &&
        keep_on_edge(point, 1.8 * me * (e2 + w * e2_difference), length_squared - e2_difference, ap, ac))
      return {point, Vec3(1 - w, 0, w)};
    return closest_on_triangle_careful(p, a, b, c);
  }
  const double va = d3 * d6 - d5 * d4, d43 = d4 - d3, d56 = d5 - d6;
  if (va < -e4 && d43 > e2_difference && d56 > e2_difference) {
    const double length_squared = d43 + d56;  // |bc|^2
    const double w = std::clamp(d43 / length_squared, 0.0, 1.0);
    const Vec3 bc = c - b, point = b + w * bc;
    if (length_squared > 4 * e2_difference &&
        keep_on_edge(point, 3.5 * me * (e2_difference + w * 2 * e2_difference), length_squared - 2 * e2_difference,
                     bp, bc))
      return {point, Vec3(0, 1 - w, w)};
    return closest_on_triangle_careful(p, a, b, c);
  }
  if (va > e4 && vb > e4 && vc > e4) {
    const double denominator = va + vb + vc;  // |ab x ac|^2 in exact arithmetic
    const double v = vb / denominator, w = vc / denominator;
    const double m = largest(), limit = allowed(m);
    // Inside. Ericson's point a + v ab + w ac where its a-priori error allows: va, vb, vc are within
    // e4 of the exact ones, so v and w within 4 e4 / (denominator - 3 e4) + 2 u (both under 1), the
    // point within 1.75 (2 me that + 6 u (M + 2 me)) (1.75 > sqrt 3). That holds on the small triangles of any
    // dense mesh, where me is far below M (e4 / denominator is some thousand u on well-shaped
    // ones); 1 - v - w stays positive, as va / denominator >= e4 / denominator > 28 u.
    // (The test below is that bound multiplied out by denominator - 3 e4: no second division.)
    const double rest = limit - 1.75 * (4 * u * me + 6 * u * (m + 2 * me)), spare = denominator - 3 * e4;
    if (spare > 0 && 14 * me * e4 <= rest * spare)
      return {a + v * ab + w * ac, Vec3(1 - v - w, v, w)};
    // Otherwise p's projection on the plane, whose distance is the plane's, known to |ap| (14 u
    // me^2 / |n| + 5 u) with n = ab x ac computed (taken here as 1.74 |ap|_inf (49.5 u me^2 / |n| +
    // 12 u), |ap| <= sqrt 3 |ap|_inf).
    const Vec3 n = ab.cross(ac);
    const double nn = n.squaredNorm(), n_length = std::sqrt(nn);
    const double error = 1.74 * largest_of(ap) * (49.5 * u * me * me / n_length + 12 * u);
    if (nn > 0 && error <= limit) return {p - (ap.dot(n) / nn) * n, Vec3(1 - v - w, v, w)};
  }
  // Undecided, a degenerate triangle (whose exact tests are all 0), or too few digits left.
  return closest_on_triangle_careful(p, a, b, c);
}

// The point alone.
__attribute__((always_inline)) inline Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
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
