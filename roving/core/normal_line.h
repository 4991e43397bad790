// The one rule for where a sample's normal line meets the test surface (DESIGN.md "distance
// semantics"), shared by every exact method so that they agree sample by sample, also where the
// line passes through a test vertex, along a test edge, or by a boundary of an open mesh.
//
// The rule. The normal line of a sample x with unit normal n is {x + s n}; s is the signed
// distance d. A triangle of the test surface is met where the line passes through the closed
// triangle or within `tolerance` of it (measured across the line): at the point of the triangle
// nearest the line, seen along n, and d is that point's s. So a line through a vertex or along
// an edge meets it (whatever the rounding of either: the triangle is closed and widened by the
// tolerance), a line through the gap of a crack narrower than twice the tolerance meets it, and
// a line passing farther than the tolerance outside a boundary edge does not. A triangle edge-on
// to the line meets it along an interval of s. Crossings count where s lies in [-h, h], widened
// by the tolerance too and then clamped into it.
// first-hit takes the largest such s (the first met from x + h n), nearest the smallest |s|.
// The tolerance is kNormalLineTolerance of the test model's bounding-box diagonal: far above the
// rounding of any input (1e-16 relative), far below any distance worth measuring, and the
// half-width of a surface-roving camera, whose pixel is where GL decides the same question.
//
// Computed exactly: every decision of the rule (the sides of the edges, edge-on, within the
// tolerance, within the view volume) by a sign that clears its rounding bound, in rationals where
// none does; s within closest_point_error_bound (geometry.h) of the rule's exact value
// (tests/exact_oracle_test.cpp).
#pragma once

#include <optional>

#include "roving/core/distance_method.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

constexpr double kNormalLineTolerance = 1e-6;

// The normal line of one sample, with the frame that passes over triangles wholly to one side.
class NormalLine {
 public:
  // `tolerance` in model units (kNormalLineTolerance times the test model's diagonal).
  NormalLine(const Vec3& x, const Vec3& n, double max_error, double tolerance);

  // The range of s over which the line meets the closed triangle (a, b, c) widened by the
  // tolerance, clipped to [-h, h]; nullopt where it does not.
  struct Interval {
    double low, high;
  };
  std::optional<Interval> crossing(const Vec3& a, const Vec3& b, const Vec3& c) const;

  const Vec3& origin() const { return x_; }
  const Vec3& direction() const { return n_; }

 private:
  Vec3 x_, n_, u_, v_;  // u, v: unit vectors across the line
  double h_, tolerance_;
};

// Keeps the crossing a semantics chooses among all those of one line.
class CrossingChoice {
 public:
  // `max_error` is h, the largest d a first-hit crossing is clamped to.
  CrossingChoice(Semantics semantics, double max_error) : semantics_(semantics), max_error_(max_error) {}
  // A crossing of triangle `face`. Where several give the chosen d, the lowest face is kept, so
  // the choice does not depend on the order crossings come in.
  void consider(const NormalLine::Interval& crossing, std::uint32_t face);
  // Whether no crossing of `face` could change the choice, whatever its interval: the chosen d
  // cannot be bettered (h for first-hit, which clamps to it; 0 for nearest) and only a lower
  // face wins the tie. Self-tests meet this on nearly every line: each passes through a vertex,
  // d = 0, and the triangles around it need not all be decided.
  bool settled_for(std::uint32_t face) const;
  // The chosen d; nullopt when no crossing was considered (a no-hit).
  const std::optional<double>& chosen() const { return best_; }
  // The chosen d with its face; nullopt for a no-hit.
  std::optional<FaceHit> chosen_hit() const {
    return best_ ? std::optional<FaceHit>(FaceHit{*best_, face_}) : std::nullopt;
  }

 private:
  void keep(double d, std::uint32_t face);
  Semantics semantics_;
  double max_error_;
  std::optional<double> best_;
  std::uint32_t face_ = 0;
};

}  // namespace roving
