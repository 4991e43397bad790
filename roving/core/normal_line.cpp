// Crossings of a sample's normal line with closed, slightly widened triangles (normal_line.h).
#include "roving/core/normal_line.h"

#include <algorithm>
#include <cmath>

namespace roving {
namespace {

// A triangle corner across the line (u, v) and along it (s).
struct Corner {
  double u, v, s;
};

// Most candidates a BVH hands over lie wholly to one side of the line, or beyond the view
// volume: the corners say so before any area or distance is computed. The margin (1e-6 of the
// tolerance, far above the rounding of the corners) keeps this test from ever rejecting a
// triangle the full rule would meet: the answers are the same, only sooner.
bool clearly_apart(const Corner (&k)[3], double tolerance, double max_error) {
  const double across = tolerance * (1 + 1e-6), along = max_error + across;
  const auto beyond = [&k](double Corner::*axis, double limit) {
    return (k[0].*axis > limit && k[1].*axis > limit && k[2].*axis > limit) ||
           (k[0].*axis < -limit && k[1].*axis < -limit && k[2].*axis < -limit);
  };
  return beyond(&Corner::u, across) || beyond(&Corner::v, across) || beyond(&Corner::s, along);
}

// The point of segment p-q nearest the line (the origin across it): its squared distance and s.
void nearest_on_segment(const Corner& p, const Corner& q, double& distance_squared, double& s) {
  const double du = q.u - p.u, dv = q.v - p.v;
  const double length_squared = du * du + dv * dv;
  double t = length_squared > 0 ? -(p.u * du + p.v * dv) / length_squared : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double cu = p.u + t * du, cv = p.v + t * dv;
  distance_squared = cu * cu + cv * cv;
  s = p.s + t * (q.s - p.s);
}

}  // namespace

NormalLine::NormalLine(const Vec3& x, const Vec3& n, double max_error, double tolerance)
    : x_(x), n_(n), h_(max_error), tolerance_(tolerance) {
  const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  u_ = n.cross(helper).normalized();
  v_ = n.cross(u_);
}

std::optional<NormalLine::Interval> NormalLine::crossing(const Vec3& a, const Vec3& b, const Vec3& c) const {
  const auto corner = [&](const Vec3& p) {
    const Vec3 r = p - x_;
    return Corner{r.dot(u_), r.dot(v_), r.dot(n_)};
  };
  const Corner k[3] = {corner(a), corner(b), corner(c)};
  if (clearly_apart(k, tolerance_, h_)) return std::nullopt;
  const double tolerance_squared = tolerance_ * tolerance_;
  double low = 0, high = 0;
  bool met = false;

  // Twice the signed area across the line, and the origin's barycentric weights.
  const double area = (k[1].u - k[0].u) * (k[2].v - k[0].v) - (k[1].v - k[0].v) * (k[2].u - k[0].u);
  double longest_squared = 0;
  for (int e = 0; e < 3; ++e) {
    const Corner &p = k[e], &q = k[(e + 1) % 3];
    longest_squared = std::max(longest_squared, (q.u - p.u) * (q.u - p.u) + (q.v - p.v) * (q.v - p.v));
  }
  const bool edge_on = !(std::abs(area) > 1e-12 * longest_squared);
  if (!edge_on) {
    const double w0 = (k[1].u * k[2].v - k[1].v * k[2].u) / area;
    const double w1 = (k[2].u * k[0].v - k[2].v * k[0].u) / area;
    const double w2 = (k[0].u * k[1].v - k[0].v * k[1].u) / area;
    if (w0 >= 0 && w1 >= 0 && w2 >= 0) {
      low = high = w0 * k[0].s + w1 * k[1].s + w2 * k[2].s;  // through the closed triangle
      met = true;
    }
  }
  if (!met) {
    // Outside (or edge-on): the boundary points within the tolerance, nearest across the line;
    // edge-on, every edge near the line contributes, spanning the triangle's s-range there.
    double best_squared = tolerance_squared;
    for (int e = 0; e < 3; ++e) {
      double distance_squared, s;
      nearest_on_segment(k[e], k[(e + 1) % 3], distance_squared, s);
      if (distance_squared > tolerance_squared) continue;
      if (edge_on) {
        // An edge along the line meets it over its whole length.
        const Corner &p = k[e], &q = k[(e + 1) % 3];
        const bool along =
            p.u * p.u + p.v * p.v <= tolerance_squared && q.u * q.u + q.v * q.v <= tolerance_squared;
        const double s_low = along ? std::min(p.s, q.s) : s, s_high = along ? std::max(p.s, q.s) : s;
        low = met ? std::min(low, s_low) : s_low;
        high = met ? std::max(high, s_high) : s_high;
        met = true;
      } else if (distance_squared <= best_squared) {
        best_squared = distance_squared;
        low = high = s;
        met = true;
      }
    }
  }
  // The view volume's ends are widened by the tolerance too (a vertex exactly at |d| = h is
  // met whatever the rounding), and d is then clamped into [-h, h].
  if (!met || high < -h_ - tolerance_ || low > h_ + tolerance_) return std::nullopt;
  low = std::clamp(low, -h_, h_);
  high = std::clamp(high, -h_, h_);
  return Interval{low, high};
}

void CrossingChoice::keep(double d, std::uint32_t face) {
  // A tie (0 and -0 too) goes to the lower face, value and all, so that neither the face nor the
  // sign of a zero depends on the order the crossings come in.
  if (best_ && d == *best_ && face_ < face) return;
  best_ = d;
  face_ = face;
}

bool CrossingChoice::settled_for(std::uint32_t face) const {
  if (!best_ || face <= face_) return false;
  return semantics_ == Semantics::FirstHit ? *best_ == max_error_ : *best_ == 0;
}

void CrossingChoice::consider(const NormalLine::Interval& crossing, std::uint32_t face) {
  if (semantics_ == Semantics::FirstHit) {
    if (!best_ || crossing.high >= *best_) keep(crossing.high, face);
    return;
  }
  // Nearest: the point of the interval closest to x.
  const double d = crossing.low <= 0 && crossing.high >= 0
                       ? 0.0
                       : (std::abs(crossing.low) < std::abs(crossing.high) ? crossing.low : crossing.high);
  // Equally near crossings on both sides: the outer one, whatever order they come in.
  if (!best_ || std::abs(d) < std::abs(*best_) || (std::abs(d) == std::abs(*best_) && d >= *best_))
    keep(d, face);
}

}  // namespace roving
