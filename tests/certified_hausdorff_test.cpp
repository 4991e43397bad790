// The certified Hausdorff interval: closed forms inside it, its width within the bound asked, every
// sampled closest-point distance below it, CGAL's bounded-error value inside it on real pairs. The
// certified share of area within tau: closed forms, the sampled share inside it, shards adding up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "analytic.h"
#include "decimate.h"
#include "roving/core/geometry.h"
#include "roving/core/normalise.h"
#include "roving/core/sample_set.h"
#include "roving/reference_cgal/cgal_reference.h"
#include "roving/reference_embree/certified_area_within.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace {

using roving::HausdorffInterval;
using roving::TriangleMesh;
using roving::Vec3;
using roving::testing::box;


TriangleMesh square(double x0, double z) {
  return TriangleMesh({{x0, 0, z}, {x0 + 1, 0, z}, {x0, 1, z}, {x0 + 1, 1, z}}, {{0, 1, 2}, {1, 3, 2}});
}

void expect_certified(const HausdorffInterval& h, double truth, double gap, const char* what) {
  EXPECT_LE(h.lower, truth * (1 + 1e-12) + 1e-15) << what;
  EXPECT_GE(h.upper, truth * (1 - 1e-12) - 1e-15) << what;
  EXPECT_LE(h.upper - h.lower, gap * (1 + 1e-12)) << what;
  EXPECT_GE(h.lower, 0) << what;
}

TEST(CertifiedHausdorff, ClosedForms) {
  // A cube inside a scaled cube: every point of the inner one is s - 1 from the outer; the outer
  // one's corners are sqrt(3) (s - 1) from the inner one's.
  const double s = 1.3;
  for (double gap : {1e-2, 1e-4, 1e-7}) {
    expect_certified(roving::certified_hausdorff(box(1), box(s), gap), s - 1, gap, "inner cube to outer");
    expect_certified(roving::certified_hausdorff(box(s), box(1), gap), std::sqrt(3.0) * (s - 1), gap,
                     "outer cube to inner");
  }
  // A unit square against itself moved by (0.3, 0, 0.4): 0.5 either way, attained at an edge.
  const HausdorffInterval planes = roving::certified_hausdorff(square(0, 0), square(0.3, 0.4), 1e-6);
  expect_certified(planes, 0.5, 1e-6, "square to moved square");
  EXPECT_NEAR(planes.lower_point.x(), 0, 1e-6);  // the edge x = 0 is the farthest from the moved square
  // A surface against itself: 0.
  const HausdorffInterval same = roving::certified_hausdorff(box(1), box(1), 1e-9);
  EXPECT_EQ(same.lower, 0);
  EXPECT_LE(same.upper, 1e-9);
}

TEST(CertifiedHausdorff, SphereAgainstItsInscribedIcosahedron) {
  // The icosahedron's vertices lie on the unit sphere; its faces' centres are its points farthest
  // from the sphere, 1 - r_i away, r_i = sqrt((5 + 2 sqrt 5) / 15) its inradius. The sphere is a
  // fine tessellation with its vertices on it, whose faces reach `chord` inside: the truth for
  // the tessellation lies in [1 - r_i - chord, 1 - r_i], and so must the interval.
  const TriangleMesh icosahedron = roving::icosphere(Vec3::Zero(), 1.0, 0);
  const TriangleMesh sphere = roving::icosphere(Vec3::Zero(), 1.0, 6);
  const double inradius = std::sqrt((5 + 2 * std::sqrt(5.0)) / 15);
  double chord = 0;  // how far inside the unit sphere the fine tessellation's faces reach
  for (std::size_t f = 0; f < sphere.triangle_count(); ++f) chord = std::max(chord, 1 - sphere.centroid(f).norm());
  const double gap = 1e-5;
  const HausdorffInterval h = roving::certified_hausdorff(icosahedron, sphere, gap);
  EXPECT_LE(h.upper - h.lower, gap * (1 + 1e-12));
  EXPECT_GE(h.upper, 1 - inradius - chord);
  EXPECT_LE(h.lower, 1 - inradius + 1e-12);
}

TEST(CertifiedHausdorff, ContainsCgalsValueAndExceedsEverySampledDistance) {
  const TriangleMesh bunny = roving::normalised(roving::testing::bunny());
  const TriangleMesh coarse = roving::decimate_quadric(bunny, 800);
  const double diagonal = bunny.bounding_box().diagonal();
  const double gap = 1e-4 * diagonal;
  for (const auto& [a, b, what] : {std::tuple{&bunny, &coarse, "bunny to 800"}, {&coarse, &bunny, "800 to bunny"}}) {
    const HausdorffInterval h = roving::certified_hausdorff(*a, *b, gap);
    EXPECT_LE(h.upper - h.lower, gap * (1 + 1e-12)) << what;
    // CGAL's value is within its own bound of the truth, which lies in [lower, upper].
    const double cgal = roving::cgal_bounded_hausdorff(*a, *b, gap);
    EXPECT_GE(cgal, h.lower - gap) << what;
    EXPECT_LE(cgal, h.upper + gap) << what;
    // Every sampled point of A is no farther from B than the upper bound.
    const roving::SampleSet samples = roving::make_samples(*a, {roving::SampleSpec::Kind::Area, 200000});
    const auto embree = roving::make_method("embree");
    embree->build(*b);
    const roving::DistanceResult r = embree->measure(samples, {roving::Semantics::Closest, diagonal});
    double sampled = 0;
    for (double d : r.signed_distance) sampled = std::max(sampled, std::abs(d));
    EXPECT_LE(sampled, h.upper * (1 + 1e-9)) << what;
    EXPECT_GE(h.lower, sampled * (1 - 1e-9)) << what << ": the vertices and subdivisions find the sampled maximum or more";
    EXPECT_NEAR((h.lower_point - h.lower_closest).norm(), h.lower, 1e-12 * diagonal) << what;
  }
}

// A triangle with two equal corners is the segment between the other two: its closest point is
// that segment's, never the NaN a 0 / 0 in an edge's test gave (which then stopped Embree's search
// for closest points: a "certified" Hausdorff of a codec's copy, its corners rounded to a grid,
// came out 1.7 times the true value, CGAL's).
TEST(ClosestOnTriangle, EqualCornersAreTheSegmentBetweenTheOthers) {
  const Vec3 a(0, 0, 0), c(4, 0, 0);
  for (const Vec3& p : {Vec3(1, 2, 0), Vec3(3, -1, 1), Vec3(-1, 1, 0), Vec3(5, 0, 2), Vec3(2, 0, 0)}) {
    const Vec3 on_segment(std::clamp(p.x(), 0.0, 4.0), 0, 0);
    for (const auto& [x, y, z] : {std::tuple{a, a, c}, {a, c, a}, {c, a, a}, {a, c, c}, {c, c, a}, {c, a, c}}) {
      const roving::TrianglePoint found = roving::closest_on_triangle(p, x, y, z);
      EXPECT_NEAR((found.point - on_segment).norm(), 0, 1e-12) << p.transpose();
      EXPECT_NEAR(found.weights.sum(), 1, 1e-12);
    }
  }
  EXPECT_EQ(roving::closest_point_on_triangle(Vec3(1, 1, 1), a, a, a), a);
}

// The bench's codec-like pair (results/mpeg.md): the bunny on a 10-bit grid against its corners
// rounded to multiples of 4, where 65 triangles have two equal corners.
TEST(CertifiedHausdorff, HoldsCgalsValueWhereTrianglesHaveEqualCorners) {
  const TriangleMesh mesh = roving::testing::bunny();
  const roving::Normalisation grid = roving::normalisation_of(mesh, 1023.0);
  const auto on_grid = [&](double step) {
    const TriangleMesh placed = roving::apply(grid, mesh);
    std::vector<Vec3> positions = placed.positions().to_vector();
    for (Vec3& p : positions) p = (p / step).array().round().matrix() * step;
    return TriangleMesh(std::move(positions), placed.triangles());
  };
  const TriangleMesh fine = on_grid(1), coarse = on_grid(4);
  std::size_t equal_corners = 0;
  for (const roving::Triangle& t : coarse.triangles()) {
    const auto& p = coarse.positions();
    equal_corners += p[t[0]] == p[t[1]] || p[t[1]] == p[t[2]] || p[t[2]] == p[t[0]];
  }
  ASSERT_GT(equal_corners, 50u);
  const double diagonal = fine.bounding_box().diagonal(), gap = 1e-4 * diagonal;
  for (const auto& [a, b, what] : {std::tuple{&fine, &coarse, "fine to coarse"}, {&coarse, &fine, "coarse to fine"}}) {
    const HausdorffInterval h = roving::certified_hausdorff(*a, *b, gap);
    const double cgal = roving::cgal_bounded_hausdorff(*a, *b, gap);
    EXPECT_GE(cgal, h.lower - gap) << what;
    EXPECT_LE(cgal, h.upper + gap) << what;
    EXPECT_TRUE(std::isfinite(h.lower) && std::isfinite(h.upper)) << what;
  }
}

// A given in parts against one B (a streamed reference's blocks): the interval still holds the
// truth within the gap, here a whole run's own; all of A as one part is the whole run, exactly.
TEST(CertifiedHausdorff, PartsOfAHoldTheWholeRunsValue) {
  const TriangleMesh bunny = roving::normalised(roving::testing::bunny());
  const TriangleMesh coarse = roving::decimate_quadric(bunny, 800);
  const double gap = 1e-4 * bunny.bounding_box().diagonal();
  const HausdorffInterval whole = roving::certified_hausdorff(bunny, coarse, gap);
  roving::CertifiedHausdorff parts(coarse, gap);
  const std::size_t n = bunny.triangle_count();
  const std::size_t cuts[] = {0, n / 7, n / 2, n - 1, n};  // parts of unequal sizes, one a single triangle
  for (std::size_t k = 0; k + 1 < std::size(cuts); ++k) parts.add(bunny, cuts[k], cuts[k + 1]);
  const HausdorffInterval h = parts.interval();
  EXPECT_LE(h.upper - h.lower, gap * (1 + 1e-12));
  EXPECT_LE(h.lower, whole.upper);
  EXPECT_LE(whole.lower, h.upper);
  // The lower end is the attained distance less the kernel's bound (docs/semantics.md).
  double largest = 0;
  for (const TriangleMesh* mesh : {&bunny, &coarse}) {
    for (const Vec3& p : mesh->positions()) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  }
  EXPECT_NEAR((h.lower_point - h.lower_closest).norm() - roving::closest_point_error_bound(largest), h.lower, 1e-15);

  roving::CertifiedHausdorff one(coarse, gap);
  EXPECT_THROW(one.interval(), roving::Error);  // nothing added yet
  one.add(bunny);
  EXPECT_EQ(one.interval().lower, whole.lower);
  EXPECT_EQ(one.interval().upper, whole.upper);
  EXPECT_EQ(one.interval().distance_queries, whole.distance_queries);
  EXPECT_THROW(one.add(bunny, 5, n + 1), roving::Error);
  EXPECT_THROW(one.add(TriangleMesh()), roving::Error);
}

TEST(CertifiedAreaWithin, ClosedForms) {
  // Every point of the inner cube is 0.3 from the outer one: none within 0.2, all within 0.4.
  const roving::AreaWithin w = roving::certified_area_within(box(1), box(1.3), {0.2, 0.4}, 1e-3, 0, 12);
  EXPECT_EQ(w.lower(0), 0);
  EXPECT_EQ(w.upper(0), 0);
  // Each of the 16,000-odd pieces loses under 2^-60 to rounding down and its area ~1e-16 to rounding.
  EXPECT_NEAR(w.lower(1), 1, 1e-13);
  EXPECT_NEAR(w.upper(1), 1, 1e-13);
  // A mesh against itself: all of it within any tau > 0 (at 0, a corner's distance to its own
  // triangle may round to 1e-17).
  const TriangleMesh bunny = roving::decimate_quadric(roving::testing::bunny(), 5000);
  const double tiny = 1e-9 * bunny.bounding_box().diagonal();
  const roving::AreaWithin self = roving::certified_area_within(bunny, bunny, {tiny}, 1e-3, 0, bunny.triangle_count());
  EXPECT_NEAR(self.lower(0), 1, 1e-13) << self.upper(0) << " " << self.triangles_split;
}

TEST(CertifiedAreaWithin, HoldsTheSampledShareAndShardsAddUp) {
  const TriangleMesh bunny = roving::decimate_quadric(roving::normalised(roving::testing::bunny()), 3000);
  const TriangleMesh coarse = roving::decimate_quadric(bunny, 800);
  const double diagonal = bunny.bounding_box().diagonal();
  const std::vector<double> taus = {1e-3 * diagonal, 3e-3 * diagonal, 1e-2 * diagonal};
  for (const auto& [a, b, what] : {std::tuple{&bunny, &coarse, "bunny to 800"}, {&coarse, &bunny, "800 to bunny"}}) {
    const roving::AreaWithin w = roving::certified_area_within(*a, *b, taus, 1e-4 * diagonal, 0, a->triangle_count());
    // The share of 100,000 area samples within tau estimates the truth, which lies in [lower,
    // upper], with a standard error of at most 0.5 / sqrt(N): 5 of them is 0.0079.
    const roving::SampleSet samples = roving::make_samples(*a, {roving::SampleSpec::Kind::Area, 100000});
    const auto embree = roving::make_method("embree");
    embree->build(*b);
    const roving::DistanceResult r = embree->measure(samples, {roving::Semantics::Closest, diagonal});
    for (std::size_t k = 0; k < taus.size(); ++k) {
      double within = 0;
      for (double d : r.signed_distance) within += std::abs(d) <= taus[k];
      within /= static_cast<double>(samples.size());
      EXPECT_GE(within, w.lower(k) - 0.0079) << what << " tau " << taus[k];
      EXPECT_LE(within, w.upper(k) + 0.0079) << what << " tau " << taus[k];
      EXPECT_LT(w.upper(k) - w.lower(k), 0.5) << what << " tau " << taus[k] << ": decided for most of the area";
    }
    // Two shards' areas add up to the whole run's, bit for bit (one direction: the other is the
    // same code, and each run takes minutes under the sanitizers).
    if (a != &bunny) continue;
    const std::size_t half = a->triangle_count() / 2;
    const roving::AreaWithin low = roving::certified_area_within(*a, *b, taus, 1e-4 * diagonal, 0, half);
    const roving::AreaWithin high = roving::certified_area_within(*a, *b, taus, 1e-4 * diagonal, half, a->triangle_count());
    for (std::size_t k = 0; k < taus.size(); ++k) {
      EXPECT_EQ(low.within[k] + high.within[k], w.within[k]) << what;
      EXPECT_EQ(low.undecided[k] + high.undecided[k], w.undecided[k]) << what;
    }
  }
}

TEST(CertifiedAreaWithin, RefusesEmptyMeshesAndBadThresholds) {
  EXPECT_THROW(roving::certified_area_within(TriangleMesh(), box(1), {0.1}, 1e-3, 0, 0), roving::Error);
  EXPECT_THROW(roving::certified_area_within(box(1), box(1), {-1}, 1e-3, 0, 12), roving::Error);
  EXPECT_THROW(roving::certified_area_within(box(1), box(1), {std::nan("")}, 1e-3, 0, 12), roving::Error);
  EXPECT_THROW(roving::certified_area_within(box(1), box(1), {0.1}, 0, 0, 12), roving::Error);
  EXPECT_THROW(roving::certified_area_within(box(1), box(1), {0.1}, 1e-3, 0, 13), roving::Error);
}

TEST(CertifiedHausdorff, RefusesEmptyMeshesAndBadGaps) {
  EXPECT_THROW(roving::certified_hausdorff(TriangleMesh(), box(1), 1e-3), roving::Error);
  EXPECT_THROW(roving::certified_hausdorff(box(1), box(1), 0), roving::Error);
  EXPECT_THROW(roving::certified_hausdorff(box(1), box(1), std::nan("")), roving::Error);
  EXPECT_THROW(roving::CertifiedHausdorff(TriangleMesh(), 1e-3), roving::Error);
  EXPECT_THROW(roving::CertifiedHausdorff(box(1), -1), roving::Error);
}

}  // namespace
