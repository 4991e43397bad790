// Every figure called exact or certified against an exact rational oracle (exact_oracle.h) on
// adversarial pairs (adversarial_pairs.h): the closest-point kernel, every closest-point method
// (Embree, CGAL, both vertex-to-plane searches) on vertex, face, area and scattered samples, and
// the certified Hausdorff interval and the certified shares within tau; every normal-line method (Embree, CGAL) first-hit and nearest. The bound is the kernel's stated one,
// closest_point_error_bound(M) with M the largest coordinate involved: 1024 ulps of it (1.1e-13 M), far below any
// distance a user measures, and far above what a correct computation rounds to. Zero
// discrepancies beyond it. A longer run by hand: ROVING_ORACLE_PAIRS=N (docs/reliability.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>

#include "adversarial_pairs.h"
#include "exact_oracle.h"
#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/normal_line.h"
#include "roving/core/rational.h"
#include "roving/reference_embree/certified_area_within.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/registry/method_registry.h"

namespace roving {
namespace {

// The sanitizer build runs a third of the pairs (its arithmetic is several times slower).
#ifndef ROVING_ORACLE_SCALE
#define ROVING_ORACLE_SCALE 1
#endif
int pair_count(int fallback) {
  const char* text = std::getenv("ROVING_ORACLE_PAIRS");
  return text ? std::max(1, std::atoi(text)) : fallback / ROVING_ORACLE_SCALE;
}

// Tallies discrepancies by kind of pair, so that a failure says which shapes went wrong.
struct Tally {
  std::size_t compared = 0, wrong = 0;
  double worst = 0;  // the largest error found, in units of the bound
  std::map<std::string, std::size_t> by_kind;
  void check(double found, double exact, double bound, const std::string& what) {
    ++compared;
    const double error = std::abs(found - exact);
    worst = std::max(worst, error / bound);
    if (!(error <= bound)) {
      if (++by_kind[what] <= 2 && wrong < 20)
        ADD_FAILURE() << what << ": found " << found << ", exact " << exact << " (error " << error << ", bound "
                      << bound << ")";
      ++wrong;
    }
  }
};

double largest(const Vec3& p) { return p.cwiseAbs().maxCoeff(); }

TEST(ExactOracle, ClosestPointKernelOnAdversarialTriangles) {
  adversarial::Choices choose(1);
  Tally tally;
  for (int k = 0; k < 20 * pair_count(1000); ++k) {
    std::string kind;
    auto t = adversarial::triangle(choose, kind);
    const double scale = std::pow(10.0, 6 * (choose.below(3) - 1));
    const Vec3 offset = choose.below(3) == 0 ? Vec3(1e6, -1e6, 3e5) : Vec3::Zero();
    for (Vec3& v : t) v = v * scale + offset;
    for (int s = 0; s < 8; ++s) {
      const double r = choose.unit();
      Vec3 p;
      switch (s % 4) {
        case 0: p = t[choose.below(3)] + scale * std::pow(10.0, -choose.below(14)) * choose.vector(); break;
        case 1: p = t[0] + r * (t[1] - t[0]) + scale * std::pow(10.0, -choose.below(14)) * choose.vector(); break;
        case 2: p = (t[0] + t[1] + t[2]) / 3 + scale * std::pow(10.0, -choose.below(14)) * choose.vector(); break;
        default: p = offset + 2 * scale * choose.vector(); break;
      }
      const TrianglePoint found = closest_on_triangle(p, t[0], t[1], t[2]);
      const double m = std::max({largest(p), largest(t[0]), largest(t[1]), largest(t[2])});
      const double exact = oracle::distance(oracle::squared_distance(p, t[0], t[1], t[2]));
      tally.check((found.point - p).norm(), exact, closest_point_error_bound(m), kind);
      // The point is the triangle's, its weights say where: non-negative, summing to 1.
      EXPECT_GE(found.weights.minCoeff(), 0) << kind;
      EXPECT_NEAR(found.weights.sum(), 1, 1e-12) << kind;
    }
  }
  std::printf("kernel: %zu points, %zu beyond the bound, worst error %.3g of the bound\n", tally.compared,
              tally.wrong, tally.worst);
  EXPECT_EQ(tally.wrong, 0u);
}

// Closest-point d of every exact method against the oracle's distance, on scattered samples and
// on REF = TEST's own vertex, face and area samples (where the exact distance is 0).
TEST(ExactOracle, EveryClosestPointMethodOnAdversarialPairs) {
  adversarial::Choices choose(2);
  std::map<std::string, Tally> tallies;
  const std::vector<std::string> methods = {"embree", "cgal", "v2p-naive", "v2p-aabb"};
  std::vector<std::unique_ptr<DistanceMethod>> made;
  for (const auto& name : methods) made.push_back(make_method(name));
  for (int k = 0; k < pair_count(300); ++k) {
    const adversarial::Pair pair = adversarial::pair(choose, 24);
    if (!(pair.test.total_area() > 0)) continue;  // no surface: the readers refuse it (bad_input_test)
    std::vector<std::pair<std::string, SampleSet>> sets = {{"scattered", pair.samples}};
    for (const char* kind : {"vertices", "faces", "area:16"}) {
      try {
        sets.emplace_back(kind, make_samples(pair.test, parse_sample_spec(kind)));
      } catch (const Error&) {  // every face degenerate: no face or area samples, rightly
      }
    }
    const double m = oracle::largest_coordinate(pair.test);
    for (std::size_t i = 0; i < methods.size(); ++i) {
      made[i]->build(pair.test);
      for (const auto& [set_name, samples] : sets) {
        const double h = 10 * (pair.test.bounding_box().diagonal() + m);
        const DistanceResult r = made[i]->measure(samples, {Semantics::Closest, h});
        for (std::size_t s = 0; s < samples.size(); ++s) {
          const Vec3& x = samples.positions[s];
          const double exact = oracle::distance(oracle::squared_distance(x, pair.test));
          const double bound = closest_point_error_bound(std::max(m, largest(x)));
          ASSERT_TRUE(r.hit[s]) << methods[i] << ": " << pair.what;
          tallies[methods[i]].check(std::abs(r.signed_distance[s]), exact, bound,
                                    methods[i] + ", " + set_name + ": " + pair.what);
        }
      }
    }
  }
  for (const auto& [name, tally] : tallies) {
    std::printf("%s: %zu samples, %zu beyond the bound, worst error %.3g of the bound\n", name.c_str(),
                tally.compared, tally.wrong, tally.worst);
    EXPECT_EQ(tally.wrong, 0u) << name;
  }
}

// First-hit and nearest d of both exact methods against the oracle's rule (exact_oracle.h's
// line_d) on the same samples: needles and caps nearly edge-on, faces edge-on and degenerate,
// lines through vertices and along edges (REF = TEST's own samples), view volumes of several
// depths. The same bound as the closest point's.
TEST(ExactOracle, EveryNormalLineMethodOnAdversarialPairs) {
  adversarial::Choices choose(4);
  std::map<std::string, Tally> tallies;
  std::size_t no_hits = 0;
  for (int k = 0; k < pair_count(300); ++k) {
    const adversarial::Pair pair = adversarial::pair(choose, 24);
    if (!(pair.test.total_area() > 0)) continue;
    std::vector<std::pair<std::string, SampleSet>> sets = {{"scattered", pair.samples}};
    for (const char* kind : {"vertices", "faces", "area:16"}) {
      try {
        sets.emplace_back(kind, make_samples(pair.test, parse_sample_spec(kind)));
      } catch (const Error&) {
      }
    }
    const double diagonal = pair.test.bounding_box().diagonal();
    const double m = oracle::largest_coordinate(pair.test);
    const double tolerance = kNormalLineTolerance * diagonal;
    const double h = diagonal * std::pow(10.0, choose.below(4) - 2.0);
    for (const std::string name : {"embree", "cgal"}) {
      const auto method = make_method(name);
      method->build(pair.test);
      for (const Semantics semantics : {Semantics::FirstHit, Semantics::Nearest}) {
        const bool first_hit = semantics == Semantics::FirstHit;
        const std::string what = name + (first_hit ? " first-hit" : " nearest");
        for (const auto& [set_name, samples] : sets) {
          const DistanceResult r = method->measure(samples, {semantics, h});
          for (std::size_t s = 0; s < samples.size(); ++s) {
            const auto exact =
                oracle::line_d(samples.positions[s], samples.normals[s], pair.test, h, tolerance, first_hit);
            ASSERT_EQ(bool(r.hit[s]), exact.has_value()) << what << ", " << set_name << ": " << pair.what;
            if (!exact) {
              ++no_hits;
              continue;
            }
            const double bound = closest_point_error_bound(std::max(m, largest(samples.positions[s])));
            tallies[what].check(r.signed_distance[s], nearest_double(*exact), bound,
                                what + ", " + set_name + ": " + pair.what);
          }
        }
      }
    }
  }
  for (const auto& [name, tally] : tallies) {
    std::printf("%s: %zu samples (no-hits apart), %zu beyond the bound, worst error %.3g of the bound\n",
                name.c_str(), tally.compared, tally.wrong, tally.worst);
    EXPECT_EQ(tally.wrong, 0u) << name;
  }
  std::printf("no-hits, equal to the oracle's: %zu\n", no_hits);
}

// The certified interval holds the exact one-sided Hausdorff distance: no less than the exact
// distance at any vertex of A (each a point of A), and its lower end attained at its own point.
TEST(ExactOracle, CertifiedHausdorffHoldsTheExactValue) {
  adversarial::Choices choose(3);
  Tally at_vertices, attained;
  for (int k = 0; k < pair_count(300); ++k) {
    const adversarial::Pair a = adversarial::pair(choose, 0), b = adversarial::pair(choose, 0);
    const HausdorffInterval h = certified_hausdorff(a.test, b.test, 1e-3 * (a.test.bounding_box().diagonal() + 1e-300));
    const double m = std::max(oracle::largest_coordinate(a.test), oracle::largest_coordinate(b.test));
    const double bound = closest_point_error_bound(m);
    double vertex_max = 0;
    const auto referenced = a.test.vertex_referenced();
    for (std::size_t v = 0; v < a.test.positions().size(); ++v) {
      if (referenced[v])
        vertex_max = std::max(vertex_max, oracle::distance(oracle::squared_distance(a.test.positions()[v], b.test)));
    }
    const std::string what = a.what + " against " + b.what;
    at_vertices.check(std::max(h.upper, vertex_max), h.upper, bound, "upper end below a vertex's distance: " + what);
    const double exact_lower = oracle::distance(oracle::squared_distance(h.lower_point, b.test));
    attained.check(std::min(h.lower, exact_lower), h.lower, bound, "lower end not attained: " + what);
  }
  std::printf("certified Hausdorff: %zu pairs, %zu upper ends and %zu lower ends beyond the bound\n",
              at_vertices.compared, at_vertices.wrong, attained.wrong);
  EXPECT_EQ(at_vertices.wrong + attained.wrong, 0u);
}

// The certified shares of A's area within tau of B (precision and recall's bounds) hold the exact
// share: their upper end no less than the area exact_oracle.h's share_bounds proves within, their
// lower end no more than the area it does not prove beyond. B is A itself (every share 1 for
// tau > 0, and at tau = 0) or A with each vertex moved by up to 5% of its diagonal. The slack,
// 1e-12 of the area, is the rounding of the pieces' areas: at most 4^6 pieces a triangle, each
// rounded to 2^-60 of the area, and a double's rounding of each area (1e-16 of it).
TEST(ExactOracle, CertifiedSharesWithinTauHoldTheExactShare) {
  adversarial::Choices choose(5);
  Tally upper_ends, lower_ends;
  double decided = 0;  // the share of the area the oracle decides, summed over pairs and taus
  for (int k = 0; k < pair_count(40); ++k) {
    const adversarial::Pair a = adversarial::pair(choose, 0);
    if (!(a.test.total_area() > 0)) continue;  // no area to share
    const double diagonal = a.test.bounding_box().diagonal();
    std::vector<Vec3> moved = a.test.positions().to_vector();
    const bool same = k % 2 == 0;
    if (!same) {
      for (Vec3& p : moved) p += 0.05 * diagonal * choose.vector();
    }
    const TriangleMesh b(moved, a.test.triangles());
    const std::vector<double> taus = {0, 1e-3 * diagonal, 1e-2 * diagonal, 0.05 * diagonal, 0.2 * diagonal};
    const AreaWithin w = certified_area_within(a.test, b, taus, 1e-3 * diagonal, 0, a.test.triangle_count());
    const oracle::ShareBounds exact = oracle::share_bounds(a.test, b, taus, 2);
    const std::string what = a.what + (same ? " against itself" : " against itself moved");
    for (std::size_t t = 0; t < taus.size(); ++t) {
      const std::string at = what + ", tau " + std::to_string(taus[t] / diagonal) + " of the diagonal";
      upper_ends.check(std::max(w.upper(t), exact.lower[t]), w.upper(t), 1e-12, "upper end below the exact share: " + at);
      lower_ends.check(std::min(w.lower(t), exact.upper[t]), w.lower(t), 1e-12, "lower end above the exact share: " + at);
      if (same && taus[t] > 0) EXPECT_EQ(exact.lower[t], 1.0) << "the oracle decides A within tau of itself: " << at;
      decided += 1 - (exact.upper[t] - exact.lower[t]);
    }
  }
  std::printf("certified shares: %zu shares, %zu upper and %zu lower ends beyond the exact share; the oracle decided "
              "%.1f%% of the area\n",
              upper_ends.compared, upper_ends.wrong, lower_ends.wrong, 100 * decided / upper_ends.compared);
  EXPECT_EQ(upper_ends.wrong + lower_ends.wrong, 0u);
}

}  // namespace
}  // namespace roving
