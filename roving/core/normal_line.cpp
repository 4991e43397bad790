// Crossings of a sample's normal line with closed, slightly widened triangles (normal_line.h).
#include "roving/core/normal_line.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "roving/core/geometry.h"
#include "roving/core/rational.h"
#include "roving/core/unreduced_rational.h"

namespace roving {
namespace {

constexpr double kUnit = 0x1p-53;  // the unit roundoff u

// A corner's offset from x across the line (u, v) and along it (s), in the line's rounded frame:
// enough to pass over the triangles that lie wholly to one side.
struct Corner {
  double u, v, s;
};

// Most candidates a BVH hands over lie wholly to one side of the line, or beyond the view
// volume: the corners say so before anything exact is computed. The margin covers the rounding
// of the offsets and of the frame (a few u of the largest coordinate), so that this test never
// rejects a triangle the exact rule meets.
bool clearly_apart(const Corner (&k)[3], double tolerance, double max_error, double largest) {
  const double across = tolerance * (1 + 1e-12) + 32 * kUnit * largest, along = max_error + across;
  const auto beyond = [&k](double Corner::*axis, double limit) {
    return (k[0].*axis > limit && k[1].*axis > limit && k[2].*axis > limit) ||
           (k[0].*axis < -limit && k[1].*axis < -limit && k[2].*axis < -limit);
  };
  return beyond(&Corner::u, across) || beyond(&Corner::v, across) || beyond(&Corner::s, along);
}

// A double with a bound on its distance from the exact value of the same expression of the same
// inputs (a running forward error analysis: each operation adds its own rounding, u of its
// result, to the errors it inherits). Decisions are taken only where the value clears its bound.
struct Bounded {
  double value, error;
};
Bounded operator+(Bounded a, Bounded b) {
  const double r = a.value + b.value;
  return {r, a.error + b.error + kUnit * std::abs(r)};
}
Bounded operator-(Bounded a, Bounded b) {
  const double r = a.value - b.value;
  return {r, a.error + b.error + kUnit * std::abs(r)};
}
bool exactly_zero(const Bounded& b) { return b.value == 0 && b.error == 0; }
Bounded operator*(Bounded a, Bounded b) {
  if (exactly_zero(a) || exactly_zero(b)) return {0, 0};  // a corner on the line: zeros stay exact
  const double r = a.value * b.value;
  // Underflow rounds absolutely, not relatively: one denormal more.
  return {r, std::abs(a.value) * b.error + std::abs(b.value) * a.error + a.error * b.error +
                 kUnit * std::abs(r) + std::numeric_limits<double>::denorm_min()};
}
Bounded operator/(Bounded a, Bounded b) {
  if (exactly_zero(a) && !exactly_zero(b)) return {0, 0};
  const double r = a.value / b.value, below = std::abs(b.value) - b.error;
  if (!(below > 0)) return {r, HUGE_VAL};  // the divisor may be 0: no bound
  return {r, (a.error + std::abs(r) * b.error) / below + kUnit * std::abs(r) +
                 std::numeric_limits<double>::denorm_min()};
}
// Orders by value: where two ends are within their bounds of each other, either is as good.
bool below(const Bounded& a, const Bounded& b) { return a.value < b.value; }
bool below(const UnreducedRational& a, const UnreducedRational& b) { return sgn(a - b) < 0; }

// Signs, decided exactly or not at all: a Bounded sign is taken where the value clears its bound
// (widened for the rounding of the bound's own arithmetic); elsewhere `undecided` is set, the
// rest of the evaluation is void, and it is redone in rationals.
struct BoundedSigns {
  bool undecided = false;
  int operator()(const Bounded& b) {
    if (exactly_zero(b)) return 0;
    if (std::abs(b.value) > b.error * (1 + 1e-9)) return b.value > 0 ? 1 : -1;
    undecided = true;
    return 0;
  }
};
struct ExactSigns {
  int operator()(const UnreducedRational& q) const { return sgn(q); }
};

Bounded number(double v, Bounded*) { return {v, 0}; }
UnreducedRational number(double v, UnreducedRational*) { return UnreducedRational(v); }

template <class N>
struct Point {
  N x, y, z;
};
template <class N>
Point<N> operator-(const Point<N>& a, const Point<N>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class N>
N dot(const Point<N>& a, const Point<N>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class N>
Point<N> cross(const Point<N>& a, const Point<N>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class N>
Point<N> point(const Vec3& v) {
  return {number(v.x(), (N*)nullptr), number(v.y(), (N*)nullptr), number(v.z(), (N*)nullptr)};
}

// The rule of normal_line.h on the line {x + s n} and the closed triangle p, in number type N:
// every decision by `sign`, nothing by a tolerance but the rule's own. In 3D terms, without the
// rounded frame: with r_i = p_i - x,
//   D_i = (r_i x r_(i+1)) . n  says on which side of edge i the line passes (their sum is the
//         triangle's normal dotted with n: 0 exactly when the triangle is edge-on to the line,
//         degenerate triangles included),
//   c_i = r_i x n              is corner i's offset across the line, times |n|,
//   t_i = r_i . n              is its s, times n . n.
// Returns the interval of s, clamped into [-h, h], or nothing.
template <class N, class Sign>
std::optional<std::pair<N, N>> crossing_rule(const Vec3& x_, const Vec3& n_, const Vec3 (&p_)[3], double h,
                                             double tolerance, double window, Sign& sign) {
  const Point<N> x = point<N>(x_), n = point<N>(n_);
  const N nn = dot(n, n);
  Point<N> c[3];
  N t[3];
  Point<N> r[3];
  for (int i = 0; i < 3; ++i) {
    r[i] = point<N>(p_[i]) - x;
    c[i] = cross(r[i], n);
    t[i] = dot(r[i], n);
  }
  N D[3];
  for (int i = 0; i < 3; ++i) D[i] = dot(cross(r[i], r[(i + 1) % 3]), n);
  const N S = D[0] + D[1] + D[2];
  const int area_sign = sign(S);
  N low{}, high{};
  bool met = false;
  if (area_sign != 0 && sign(D[0]) * area_sign >= 0 && sign(D[1]) * area_sign >= 0 &&
      sign(D[2]) * area_sign >= 0) {
    // Through the closed triangle: D_i / S is the weight of the corner opposite edge i.
    low = high = (D[1] * t[0] + D[2] * t[1] + D[0] * t[2]) / (S * nn);
    met = true;
  } else {
    // Outside, or edge-on: the boundary's points within the tolerance across the line. Outside,
    // the one nearest the line (unique: the triangle is convex seen along n); edge-on, every edge
    // near the line contributes, an edge along it over its whole length.
    const N tolerance_nn = number(tolerance, (N*)nullptr) * number(tolerance, (N*)nullptr) * nn;
    N best = tolerance_nn;
    const auto keep_lower = [](N& kept, const N& v) {
      if (below(v, kept)) kept = v;
    };
    const auto keep_higher = [](N& kept, const N& v) {
      if (below(kept, v)) kept = v;
    };
    for (int e = 0; e < 3; ++e) {
      const int q = (e + 1) % 3;
      const Point<N> along = c[q] - c[e];
      const N length = dot(along, along);
      N f = number(0, (N*)nullptr);  // the nearest point's parameter on the edge
      Point<N> nearest = c[e];
      if (sign(length) > 0) {
        const N towards = number(0, (N*)nullptr) - dot(c[e], along);
        if (sign(towards - length) >= 0) {
          f = number(1, (N*)nullptr);
          nearest = c[q];
        } else if (sign(towards) > 0) {
          f = towards / length;
          nearest = {c[e].x + f * along.x, c[e].y + f * along.y, c[e].z + f * along.z};
        }
      }
      const N distance = dot(nearest, nearest);
      if (sign(distance - tolerance_nn) > 0) continue;
      const N s = (t[e] + f * (t[q] - t[e])) / nn;
      if (area_sign == 0) {
        N s_low = s, s_high = s;
        if (sign(dot(c[e], c[e]) - tolerance_nn) <= 0 && sign(dot(c[q], c[q]) - tolerance_nn) <= 0) {
          s_low = s_high = t[e] / nn;
          const N other = t[q] / nn;
          keep_lower(s_low, other);
          keep_higher(s_high, other);
        }
        if (!met) low = s_low, high = s_high;
        keep_lower(low, s_low);
        keep_higher(high, s_high);
        met = true;
      } else if (sign(distance - best) <= 0) {
        best = distance;
        low = high = s;
        met = true;
      }
    }
  }
  // The view volume's ends are widened by the tolerance too (a vertex exactly at |d| = h is met
  // whatever the rounding), and d is then clamped into [-h, h].
  const N w = number(window, (N*)nullptr);
  if (!met || sign(high + w) < 0 || sign(low - w) > 0) return std::nullopt;
  const N top = number(h, (N*)nullptr), bottom = number(-h, (N*)nullptr);
  for (N* end : {&low, &high}) {
    if (below(*end, bottom)) *end = bottom;
    if (below(top, *end)) *end = top;
  }
  return std::make_pair(low, high);
}

// The common cases in plain double, each with an a-priori bound on its rounding (the offsets r
// are within u |r| of p - x, n within a few u of unit): the line clearly through the triangle's
// interior, or clearly outside it and farther than the tolerance from every edge. With R the
// offsets' largest coordinate, each D_i is within 64 u R^2 of the exact one, each t_i within 12 u R.
struct FastCase {
  enum { Undecided, Through, Missed } kind = Undecided;
  double s = 0;
};
FastCase fast_case(const Vec3 (&r)[3], const Corner (&k)[3], const Vec3& n, double tolerance, double allowed) {
  constexpr double u = kUnit;
  const double R = std::max({r[0].cwiseAbs().maxCoeff(), r[1].cwiseAbs().maxCoeff(), r[2].cwiseAbs().maxCoeff()});
  const double error_D = 64 * u * R * R;
  const double D[3] = {r[0].cross(r[1]).dot(n), r[1].cross(r[2]).dot(n), r[2].cross(r[0]).dot(n)};
  const auto positive = [&](double v) { return v > error_D; };
  const auto negative = [&](double v) { return v < -error_D; };
  if ((positive(D[0]) && positive(D[1]) && positive(D[2])) || (negative(D[0]) && negative(D[1]) && negative(D[2]))) {
    const double S = D[0] + D[1] + D[2], T = std::max({std::abs(k[0].s), std::abs(k[1].s), std::abs(k[2].s)});
    const double s = (D[1] * k[0].s + D[2] * k[1].s + D[0] * k[2].s) / S;  // n . n = 1 within 4 u
    // The weights D_i / S are in [0, 1]: the numerator errs by 12 u R |S| + 3 T error_D + 4 u T |S|,
    // S by 3 error_D + 2 u |S|.
    const double error_S = 3 * error_D + 2 * u * std::abs(S);
    const double error_numerator = (12 * u * R + 4 * u * T) * std::abs(S) + 3 * T * error_D;
    const double error = (error_numerator + std::abs(s) * error_S) / (std::abs(S) - error_S) + 8 * u * std::abs(s);
    if (error * (1 + 1e-9) <= allowed) return {FastCase::Through, s};
    return {};
  }
  const bool mixed = (positive(D[0]) || positive(D[1]) || positive(D[2])) &&
                     (negative(D[0]) || negative(D[1]) || negative(D[2]));
  if (!mixed) return {};
  // Outside: missed where every edge passes farther than the tolerance (measured in the rounded
  // frame, within 16 u R of the exact distance across).
  const double limit = tolerance + 64 * u * R;
  for (int e = 0; e < 3; ++e) {
    const Corner &p = k[e], &q = k[(e + 1) % 3];
    const double du = q.u - p.u, dv = q.v - p.v, length_squared = du * du + dv * dv;
    const double f = length_squared > 0 ? std::clamp(-(p.u * du + p.v * dv) / length_squared, 0.0, 1.0) : 0.0;
    const double cu = p.u + f * du, cv = p.v + f * dv;
    if (!(cu * cu + cv * cv > limit * limit)) return {};
  }
  return {FastCase::Missed, 0};
}

}  // namespace

NormalLine::NormalLine(const Vec3& x, const Vec3& n, double max_error, double tolerance)
    : x_(x), n_(n), h_(max_error), tolerance_(tolerance) {
  const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  u_ = n.cross(helper).normalized();
  v_ = n.cross(u_);
}

std::optional<NormalLine::Interval> NormalLine::crossing(const Vec3& a, const Vec3& b, const Vec3& c) const {
  const Vec3 p[3] = {a, b, c};
  double largest = x_.cwiseAbs().maxCoeff();
  Vec3 r[3];
  Corner k[3];
  for (int i = 0; i < 3; ++i) {
    r[i] = p[i] - x_;
    k[i] = Corner{r[i].dot(u_), r[i].dot(v_), r[i].dot(n_)};
    largest = std::max(largest, p[i].cwiseAbs().maxCoeff());
  }
  if (clearly_apart(k, tolerance_, h_, largest)) return std::nullopt;
  const double window = h_ + tolerance_;
  const double allowed = closest_point_error_bound(largest);
  const FastCase fast = fast_case(r, k, n_, tolerance_, allowed);
  if (fast.kind == FastCase::Missed) return std::nullopt;
  if (fast.kind == FastCase::Through) {
    // The window's decision needs s clear of its ends by the bound.
    if (fast.s < -window - allowed || fast.s > window + allowed) return std::nullopt;
    if (fast.s > -window + allowed && fast.s < window - allowed)
      return Interval{std::clamp(fast.s, -h_, h_), std::clamp(fast.s, -h_, h_)};
  }
  // Otherwise with running error bounds; in rationals where a sign is undecided or s is not
  // known to the kernel's bound (needles and caps nearly edge-on, lines through an edge).
  BoundedSigns bounded;
  const auto careful = crossing_rule<Bounded>(x_, n_, p, h_, tolerance_, window, bounded);
  if (!bounded.undecided &&
      (!careful || (careful->first.error <= allowed && careful->second.error <= allowed))) {
    if (!careful) return std::nullopt;
    return Interval{careful->first.value, careful->second.value};
  }
  ExactSigns exact;
  const auto slow = crossing_rule<UnreducedRational>(x_, n_, p, h_, tolerance_, window, exact);
  if (!slow) return std::nullopt;
  return Interval{nearest_double(to_mpq(slow->first)), nearest_double(to_mpq(slow->second))};
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
