// The exact oracle: squared distances from a point to triangles in rational arithmetic (GMP), by
// a formulation of its own: the least over every candidate point of the triangle (its corners, the
// feet of the perpendiculars on its edges that fall within them, the foot on its plane where that
// falls within the triangle by three exact orientation tests). No region logic, no shared code
// with roving/core/geometry.cpp, so that the two can disagree.
#pragma once

#include <gmpxx.h>

#include <array>
#include <cmath>
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

// The exact squared distance from p to the closed triangle (a, b, c), whatever its shape.
inline mpq_class squared_distance(const Vec3& p_, const Vec3& a_, const Vec3& b_, const Vec3& c_) {
  const Q3 p = q3(p_);
  const std::array<Q3, 3> v = {q3(a_), q3(b_), q3(c_)};
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

// The distance, within an ulp or two: the square root of the nearest double.
inline double distance(const mpq_class& squared) { return std::sqrt(squared.get_d()); }

// The largest absolute coordinate of a mesh: the scale of its rounding.
inline double largest_coordinate(const TriangleMesh& mesh) {
  double m = 0;
  for (const Vec3& p : mesh.positions()) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

}  // namespace roving::oracle
