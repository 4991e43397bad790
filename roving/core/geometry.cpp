// The exact closest point on a triangle (the inline fast path is in geometry.h) and Morton codes.
#include "roving/core/geometry.h"

#include "roving/core/rational.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace roving {

namespace {

// The low 10 bits of v spread to every third position (one axis of a Morton code).
std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t x = v & 0x3ff;
  x = (x | (x << 16)) & 0x30000ff;
  x = (x | (x << 8)) & 0x300f00f;
  x = (x | (x << 4)) & 0x30c30c3;
  x = (x | (x << 2)) & 0x9249249;
  return x;
}

// A point in rational coordinates: every double is one, and sums, products and quotients of them
// are exact.
struct Exact {
  mpq_class x, y, z;
  explicit Exact(const Vec3& v) : x(v.x()), y(v.y()), z(v.z()) {}
  Exact(mpq_class x_, mpq_class y_, mpq_class z_) : x(std::move(x_)), y(std::move(y_)), z(std::move(z_)) {}
  Exact operator-(const Exact& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Exact operator+(const Exact& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Exact operator*(const mpq_class& s) const { return {x * s, y * s, z * s}; }
  mpq_class dot(const Exact& o) const { return x * o.x + y * o.y + z * o.z; }
  Exact cross(const Exact& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
};

Vec3 nearest(const Exact& e) {
  return Vec3(nearest_double(e.x), nearest_double(e.y), nearest_double(e.z));
}

}  // namespace

// mpq_class::get_d truncates; rounded to nearest through mpfr-free means: a double's 53 bits of
// the quotient, corrected by one comparison.
double nearest_double(const mpq_class& q) {
  const double t = q.get_d();  // truncated towards zero
  const double away = std::nextafter(t, q >= 0 ? HUGE_VAL : -HUGE_VAL);
  const mpq_class error_t = abs(q - mpq_class(t)), error_away = abs(q - mpq_class(away));
  return error_away < error_t ? away : t;
}

TrianglePoint closest_on_triangle_careful(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  constexpr double u = 0x1p-53;
  // The boundary: each edge's closest point, a clamped parameter (well conditioned at any length:
  // a segment's distance is within a few u of the offsets' length).
  const std::array<Vec3, 3> corner = {a, b, c};
  TrianglePoint best{a, Vec3(1, 0, 0)};
  double best_squared = std::numeric_limits<double>::infinity();
  for (int e = 0; e < 3; ++e) {
    const Vec3& from = corner[e];
    const Vec3 along = corner[(e + 1) % 3] - from;
    const double length_squared = along.squaredNorm();
    const double t = length_squared > 0 ? std::clamp((p - from).dot(along) / length_squared, 0.0, 1.0) : 0.0;
    const Vec3 point = from + t * along;
    const double squared = (point - p).squaredNorm();
    if (squared < best_squared) {
      best_squared = squared;
      best.point = point;
      best.weights = Vec3::Zero();
      best.weights[e] = 1 - t;
      best.weights[(e + 1) % 3] = t;
    }
  }
  if (best_squared == 0) return best;  // p on an edge: nothing is nearer
  // The projection's barycentric weights of b and c, with their rounding bound (the numerators
  // n . (ap x ac) and n . (ab x ap) to 64 u |ap| L (L^2 + |n|), L the longest of ab and ac).
  const Vec3 ab = b - a, ac = c - a, ap = p - a, n = ab.cross(ac);
  const double nn = n.squaredNorm(), n_length = std::sqrt(nn);
  if (!(nn > 0)) return closest_on_triangle_exact(p, a, b, c);
  const double length = std::max(ab.norm(), ac.norm()), offset = ap.norm();
  const double v = n.dot(ap.cross(ac)) / nn, w = n.dot(ab.cross(ap)) / nn;
  const double e_weight = 64 * u * offset * length * (length * length + n_length) / nn;
  const double lowest = std::min({v, w, 1 - v - w});
  // Clearly outside across an edge: the closest point is on the boundary, found above.
  if (lowest < -2 * e_weight) return best;
  double distance = std::sqrt(best_squared);
  if (lowest >= 0) {
    const Vec3 point = a + v * ab + w * ac;
    const double squared = (point - p).squaredNorm();
    if (squared < best_squared) {
      best = {point, Vec3(1 - v - w, v, w)};
      distance = std::sqrt(squared);
    }
  }
  // Inside, or too near the boundary to tell: the exact distance is at least the plane's (less
  // its rounding: 16.5 u |ap| L^2 / |n| + 12 u |ap|), and the point found is the triangle's.
  const double plane = std::abs(ap.dot(n)) / n_length - offset * (16.5 * u * length * length / n_length + 12 * u);
  const double largest = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff(),
                                   p.cwiseAbs().maxCoeff()});
  if (distance * (1 + 4 * u) - plane <= closest_point_error_bound(largest) - 8 * u * largest) return best;
  return closest_on_triangle_exact(p, a, b, c);
}

TrianglePoint closest_on_triangle_exact(const Vec3& p_, const Vec3& a_, const Vec3& b_, const Vec3& c_) {
  if (!(p_.allFinite() && a_.allFinite() && b_.allFinite() && c_.allFinite())) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {Vec3::Constant(nan), Vec3::Constant(nan)};
  }
  if (p_ == a_) return {a_, Vec3(1, 0, 0)};
  if (p_ == b_) return {b_, Vec3(0, 1, 0)};
  if (p_ == c_) return {c_, Vec3(0, 0, 1)};
  const std::array<Exact, 3> corner = {Exact(a_), Exact(b_), Exact(c_)};
  const Exact p(p_);
  const Exact ab = corner[1] - corner[0], ac = corner[2] - corner[0], ap = p - corner[0];
  const Exact n = ab.cross(ac);
  const mpq_class nn = n.dot(n);
  if (nn > 0) {
    // The projection's barycentric weights of b and c: n . (ap x ac) / |n|^2 and n . (ab x ap) / |n|^2.
    const mpq_class v = n.dot(ap.cross(ac)) / nn, w = n.dot(ab.cross(ap)) / nn;
    if (v >= 0 && w >= 0 && v + w <= 1) {
      const mpq_class u = 1 - v - w;
      return {nearest(corner[0] + ab * v + ac * w), Vec3(nearest_double(u), nearest_double(v), nearest_double(w))};
    }
  }
  // Outside the triangle, or a triangle that is a segment or a point: the nearest point of the
  // three edges, each a segment (or a point where its corners are equal). Ties go to the first edge.
  bool found = false;
  mpq_class best_squared, best_t;
  int best_edge = 0;
  Exact best_point = corner[0];
  for (int e = 0; e < 3; ++e) {
    const Exact& from = corner[e];
    const Exact along = corner[(e + 1) % 3] - from;
    const mpq_class length_squared = along.dot(along);
    mpq_class t = 0;
    if (length_squared > 0) {
      t = (p - from).dot(along) / length_squared;
      if (t < 0) t = 0;
      if (t > 1) t = 1;
    }
    const Exact point = from + along * t;
    const Exact offset = point - p;
    const mpq_class squared = offset.dot(offset);
    if (!found || squared < best_squared) {
      found = true;
      best_squared = squared;
      best_t = t;
      best_edge = e;
      best_point = point;
    }
  }
  Vec3 weights = Vec3::Zero();
  weights[best_edge] = nearest_double(1 - best_t);
  weights[(best_edge + 1) % 3] = nearest_double(best_t);
  return {nearest(best_point), weights};
}

std::uint64_t morton_code(const Vec3& p, const BoundingBox& box) {
  const Vec3 scale = (1023.0 / box.size().array().max(1e-300)).matrix();
  const Vec3 cell = (p - box.min).cwiseProduct(scale);
  std::uint64_t code = 0;
  for (int axis = 0; axis < 3; ++axis)
    code |= spread_bits(static_cast<std::uint32_t>(std::clamp(cell[axis], 0.0, 1023.0))) << axis;
  return code;
}

}  // namespace roving
