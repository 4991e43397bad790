// The exact oracle: squared distances from a point to triangles in rational arithmetic (GMP), by
// a formulation of its own: the least over every candidate point of the triangle (its corners, the
// feet of the perpendiculars on its edges that fall within them, the foot on its plane where that
// falls within the triangle by three exact orientation tests). No region logic, no shared code
// with roving/core/geometry.cpp, so that the two can disagree.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving::oracle {

struct Q3 {
  mpq_class x, y, z;
};
inline Q3 q3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Q3 operator-(const Q3& a, const Q3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Q3 operator+(const Q3& a, const Q3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Q3 operator*(const mpq_class& s, const Q3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline mpq_class dot(const Q3& a, const Q3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Q3 cross(const Q3& a, const Q3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// The exact squared distance from p to the closed triangle (v[0], v[1], v[2]), whatever its shape.
inline mpq_class squared_distance(const Q3& p, const std::array<Q3, 3>& v) {
  mpq_class best = dot(p - v[0], p - v[0]);
  const auto consider = [&best, &p](const Q3& candidate) {
    const mpq_class d = dot(candidate - p, candidate - p);
    if (d < best) best = d;
  };
  consider(v[1]);
  consider(v[2]);
  for (int e = 0; e < 3; ++e) {
    const Q3 along = v[(e + 1) % 3] - v[e];
    const mpq_class length = dot(along, along);
    if (length == 0) continue;
    const mpq_class t = dot(p - v[e], along) / length;
    if (t > 0 && t < 1) consider(v[e] + t * along);
  }
  const Q3 n = cross(v[1] - v[0], v[2] - v[0]);
  const mpq_class nn = dot(n, n);
  if (nn > 0) {
    const Q3 foot = p - (dot(p - v[0], n) / nn) * n;
    bool inside = true;
    for (int e = 0; e < 3; ++e) inside = inside && sgn(dot(n, cross(v[(e + 1) % 3] - v[e], foot - v[e]))) >= 0;
    if (inside) consider(foot);
  }
  return best;
}
inline mpq_class squared_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return squared_distance(q3(p), {q3(a), q3(b), q3(c)});
}

// The exact squared distance from p to a mesh's triangles.
inline mpq_class squared_distance(const Vec3& p, const TriangleMesh& mesh) {
  const auto& x = mesh.positions();
  bool first = true;
  mpq_class best;
  for (const Triangle& t : mesh.triangles()) {
    mpq_class d = squared_distance(p, x[t[0]], x[t[1]], x[t[2]]);
    if (first || d < best) best = d, first = false;
  }
  return best;
}

// Bounds on the share of A's area within each tau of B, exactly decided: a piece of A's triangle is
// within tau where its three corners are within tau of one triangle of B (the distance to a convex
// set is convex), beyond where, for every triangle of B, its centre's distance exceeds tau plus the
// piece's reach (the distance is 1-Lipschitz). Pieces neither decides are split in four, midpoints
// exact, to `depth`. The truth lies in [within, 1 - beyond]; only the pieces' areas (a triangle's
// area / 4^depth, in doubles) round.
struct ShareBounds {
  std::vector<double> lower, upper;
};
inline ShareBounds share_bounds(const TriangleMesh& a, const TriangleMesh& b, const std::vector<double>& taus,
                                int depth) {
  const std::size_t n = taus.size();
  std::vector<mpq_class> squared_tau;
  for (double tau : taus) squared_tau.push_back(mpq_class(tau) * mpq_class(tau));
  std::vector<std::array<Q3, 3>> b_triangles;
  for (const Triangle& t : b.triangles())
    b_triangles.push_back({q3(b.positions()[t[0]]), q3(b.positions()[t[1]]), q3(b.positions()[t[2]])});
  std::vector<double> within(n, 0), beyond(n, 0);
  // Decides what it can of one piece of `area`, and splits what it cannot.
  std::function<void(const std::array<Q3, 3>&, double, int, std::vector<bool>)> classify =
      [&](const std::array<Q3, 3>& piece, double area, int level, std::vector<bool> open) {
        const Q3 centre = mpq_class(1, 3) * (piece[0] + piece[1] + piece[2]);
        mpq_class reach2 = 0;  // the squared reach from the centre
        for (const Q3& corner : piece) reach2 = std::max(reach2, dot(corner - centre, corner - centre));
        std::vector<bool> is_within(n, false), is_beyond(n, true);
        for (const auto& t : b_triangles) {
          mpq_class corners2 = 0;
          for (const Q3& corner : piece) corners2 = std::max(corners2, squared_distance(corner, t));
          const mpq_class centre2 = squared_distance(centre, t);
          for (std::size_t k = 0; k < n; ++k) {
            if (!open[k]) continue;
            if (corners2 <= squared_tau[k]) is_within[k] = true;
            // centre's distance > tau + reach: d^2 - tau^2 - reach^2 > 0 and its square > 4 tau^2 reach^2.
            const mpq_class gap = centre2 - squared_tau[k] - reach2;
            if (!(gap > 0 && gap * gap > 4 * squared_tau[k] * reach2)) is_beyond[k] = false;
          }
        }
        bool split = false;
        for (std::size_t k = 0; k < n; ++k) {
          if (!open[k]) continue;
          if (is_within[k]) {
            within[k] += area, open[k] = false;
          } else if (is_beyond[k]) {
            beyond[k] += area, open[k] = false;
          } else {
            split = true;
          }
        }
        if (!split || level == depth) return;
        const Q3 m01 = mpq_class(1, 2) * (piece[0] + piece[1]), m12 = mpq_class(1, 2) * (piece[1] + piece[2]),
                 m20 = mpq_class(1, 2) * (piece[2] + piece[0]);
        for (const auto& child : {std::array<Q3, 3>{piece[0], m01, m20}, std::array<Q3, 3>{m01, piece[1], m12},
                                  std::array<Q3, 3>{m20, m12, piece[2]}, std::array<Q3, 3>{m01, m12, m20}})
          classify(child, area / 4, level + 1, open);
      };
  const auto& x = a.positions();
  for (const Triangle& t : a.triangles()) {
    const double area = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
    if (area > 0) classify({q3(x[t[0]]), q3(x[t[1]]), q3(x[t[2]])}, area, 0, std::vector<bool>(n, true));
  }
  ShareBounds bounds;
  for (std::size_t k = 0; k < n; ++k) {
    bounds.lower.push_back(within[k] / a.total_area());
    bounds.upper.push_back(1 - beyond[k] / a.total_area());
  }
  return bounds;
}

// The normal line's rule (roving/core/normal_line.h) on one triangle, exactly, by a formulation
// of its own: the line's crossing with the triangle's plane and a barycentric inside test; else
// each edge's nearest point to the line seen along n (the edge projected on the plane across the
// line). Returns the interval of s (the point is x + s n), not yet clamped.
struct SInterval {
  mpq_class low, high;
};
inline std::optional<SInterval> line_crossing(const Vec3& x_, const Vec3& n_, const Vec3& a_, const Vec3& b_,
                                              const Vec3& c_, const mpq_class& tolerance) {
  const Q3 x = q3(x_), n = q3(n_);
  const std::array<Q3, 3> v = {q3(a_), q3(b_), q3(c_)};
  const mpq_class nn = dot(n, n);
  const Q3 normal = cross(v[1] - v[0], v[2] - v[0]);
  const mpq_class facing = dot(normal, n);
  if (facing != 0) {
    const mpq_class s = dot(normal, v[0] - x) / facing;
    const Q3 at = x + s * n;
    bool inside = true;
    for (int e = 0; e < 3; ++e) inside = inside && sgn(dot(normal, cross(v[(e + 1) % 3] - v[e], at - v[e]))) >= 0;
    if (inside) return SInterval{s, s};
  }
  const auto across = [&](const Q3& p) { return p - (dot(p, n) / nn) * n; };
  const mpq_class limit = tolerance * tolerance;
  std::optional<SInterval> met;
  mpq_class best = limit;
  for (int e = 0; e < 3; ++e) {
    const Q3 p = v[e] - x, q = v[(e + 1) % 3] - x;
    const Q3 a = across(p), d = across(q) - a;
    mpq_class f = 0;
    if (dot(d, d) != 0) {
      f = -dot(a, d) / dot(d, d);
      if (f < 0) f = 0;
      if (f > 1) f = 1;
    }
    const Q3 nearest = a + f * d;
    const mpq_class distance = dot(nearest, nearest);
    if (distance > limit) continue;
    const mpq_class s = dot(p + f * (q - p), n) / nn;
    if (facing != 0) {  // outside: the one point nearest the line
      if (distance <= best) best = distance, met = SInterval{s, s};
      continue;
    }
    SInterval piece{s, s};  // edge-on: every edge near the line; one along it all its length
    if (dot(a, a) <= limit && dot(across(q), across(q)) <= limit) {
      const mpq_class sp = dot(p, n) / nn, sq = dot(q, n) / nn;
      piece = sp < sq ? SInterval{sp, sq} : SInterval{sq, sp};
    }
    if (!met) met = piece;
    if (piece.low < met->low) met->low = piece.low;
    if (piece.high > met->high) met->high = piece.high;
  }
  return met;
}

// The d the rule gives a sample against a whole mesh: first-hit the top of every crossing's
// interval, nearest the point of any interval nearest x (the outer one of two equally near);
// within [-h, h] widened by the tolerance (window, the double h + tolerance), clamped into it.
inline std::optional<mpq_class> line_d(const Vec3& x, const Vec3& n, const TriangleMesh& mesh, double h,
                                       double tolerance, bool first_hit) {
  const mpq_class window = mpq_class(h + tolerance), top = h, tol = tolerance;
  std::optional<mpq_class> chosen;
  const auto& p = mesh.positions();
  for (const Triangle& t : mesh.triangles()) {
    std::optional<SInterval> c = line_crossing(x, n, p[t[0]], p[t[1]], p[t[2]], tol);
    if (!c || c->high < -window || c->low > window) continue;
    for (mpq_class* end : {&c->low, &c->high}) {
      if (*end > top) *end = top;
      if (*end < -top) *end = -top;
    }
    mpq_class d = c->high;
    if (!first_hit) d = c->low <= 0 && c->high >= 0 ? mpq_class(0) : (abs(c->low) < abs(c->high) ? c->low : c->high);
    if (!chosen || (first_hit ? d > *chosen : (abs(d) < abs(*chosen) || (abs(d) == abs(*chosen) && d > *chosen))))
      chosen = d;
  }
  return chosen;
}

// The distance, within an ulp or two: the square root of the nearest double.
inline double distance(const mpq_class& squared) { return std::sqrt(squared.get_d()); }

// The largest absolute coordinate of a mesh: the scale of its rounding.
inline double largest_coordinate(const TriangleMesh& mesh) {
  double m = 0;
  for (const Vec3& p : mesh.positions()) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

}  // namespace roving::oracle
