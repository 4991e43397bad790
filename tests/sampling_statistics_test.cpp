// Sample sets and statistics: counts on the real bunny, reproducibility, and statistics of
// hand-computed cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>

#include "roving/core/confidence.h"
#include "roving/core/error.h"
#include "roving/core/mersenne_twister.h"
#include "roving/core/mesh_orientation.h"
#include "roving/core/radix_sort.h"
#include "roving/core/sample_set.h"
#include "roving/core/statistics.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

TEST(Samples, BunnyFacesGiveThePapersCount) {
  const SampleSet samples = make_samples(testing::bunny(), {});
  EXPECT_EQ(samples.size(), 69451u);  // the paper's Table 1
  EXPECT_EQ(samples.skipped_degenerate_faces, 0u);
  double area = 0;
  for (double w : samples.weights) area += w;
  EXPECT_NEAR(area, testing::bunny().total_area(), 1e-12 * area);
}

TEST(Samples, VertexSamplingSkipsTheBunnysUnreferencedVertices) {
  const TriangleMesh& bunny = testing::bunny();
  EXPECT_EQ(bunny.vertex_count(), 35947u);
  EXPECT_EQ(bunny.unreferenced_vertex_count(), 1113u);
  const SampleSet samples = make_samples(bunny, {SampleSpec::Kind::Vertices});
  EXPECT_EQ(samples.skipped_unreferenced_vertices, 1113u);
  EXPECT_EQ(samples.size() + samples.skipped_unreferenced_vertices + samples.skipped_zero_normal_vertices,
            35947u);
  for (const Vec3& n : samples.normals) ASSERT_NEAR(n.norm(), 1.0, 1e-12);
}

// The bunny has unreferenced vertices, so vertex samples are compacted; each kind must come out
// the same whether the mesh keeps its geometry or gives it up, and the mesh must still report
// what it was.
TEST(Samples, ReleasingTheReferenceGivesTheSameSamples) {
  for (const SampleSpec& spec :
       {SampleSpec{}, SampleSpec{SampleSpec::Kind::Vertices}, SampleSpec{SampleSpec::Kind::Area, 500}}) {
    const SampleSet kept = make_samples(testing::bunny(), spec);
    TriangleMesh bunny = testing::bunny();
    const SampleSet released = make_samples_releasing(bunny, spec);
    EXPECT_EQ(released.positions, kept.positions) << spec.to_string();
    EXPECT_EQ(released.normals, kept.normals) << spec.to_string();
    EXPECT_EQ(released.weights, kept.weights) << spec.to_string();
    EXPECT_EQ(released.elements, kept.elements) << spec.to_string();
    EXPECT_EQ(released.skipped_unreferenced_vertices, kept.skipped_unreferenced_vertices);
    EXPECT_EQ(released.kind, kept.kind);
    EXPECT_TRUE(bunny.positions().empty() && bunny.triangles().empty()) << "the geometry is gone";
    EXPECT_EQ(bunny.vertex_count(), 35947u);
    EXPECT_EQ(bunny.triangle_count(), 69451u);
    EXPECT_EQ(bunny.total_area(), testing::bunny().total_area());
    EXPECT_EQ(bunny.bounding_box().diagonal(), testing::bunny().bounding_box().diagonal());
  }
}

// A mesh over a caller's memory (Python's NumPy arrays) reads it in place, keeps the lender alive
// as long as any copy of the mesh, and gives the same samples as a mesh of its own.
TEST(Samples, LentGeometryIsReadInPlace) {
  const TriangleMesh& own = testing::bunny();
  auto buffers = std::make_shared<std::pair<std::vector<Vec3>, std::vector<Triangle>>>(
      own.positions().to_vector(), own.triangles().to_vector());
  const std::weak_ptr<const void> watch = buffers;
  std::optional<TriangleMesh> lent;
  lent.emplace(SharedArray<Vec3>(buffers->first.data(), buffers->first.size(), buffers),
               SharedArray<Triangle>(buffers->second.data(), buffers->second.size(), buffers));
  const Vec3* in_place = buffers->first.data();
  buffers.reset();
  EXPECT_EQ(lent->positions().data(), in_place) << "no copy";
  EXPECT_TRUE(lent->positions().lent() && !own.positions().lent());
  EXPECT_EQ(make_samples(*lent, {}).positions, make_samples(own, {}).positions);
  TriangleMesh copy = *lent;
  lent.reset();
  EXPECT_FALSE(watch.expired()) << "a copy of the mesh keeps the lender";
  const SampleSet released = make_samples_releasing(copy, {SampleSpec::Kind::Vertices});
  EXPECT_EQ(released.positions, make_samples(own, {SampleSpec::Kind::Vertices}).positions);
  EXPECT_TRUE(watch.expired()) << "giving up the geometry lets the lender go";
}

TEST(Samples, AreaSamplingIsReproducibleAndLiesOnTheSurface) {
  const TriangleMesh cube = testing::box(1.0);
  const SampleSet a = make_samples(cube, parse_sample_spec("area:1000"));
  const SampleSet b = make_samples(cube, parse_sample_spec("area:1000"));
  ASSERT_EQ(a.size(), 1000u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a.positions[k], b.positions[k]);
    // On the box surface: the largest |coordinate| is 1, and the normal is the matching axis.
    EXPECT_NEAR(a.positions[k].cwiseAbs().maxCoeff(), 1.0, 1e-12);
    Eigen::Index axis;
    a.positions[k].cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(std::abs(a.normals[k][axis]), 1.0, 1e-12);
  }
}

TEST(Samples, BadSpecsNameTheOption) {
  for (const char* bad : {"", "face", "area:", "area:0", "area:-3", "area:12x", "area:99999999999999"}) {
    try {
      parse_sample_spec(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--samples"), std::string::npos) << e.what();
    }
  }
}

// Faces whose area is positive but far too small for a normal (corners collinear but for 1e-21,
// at edges of 1e-6: below double's resolution of a normal): no face, vertex or area samples, refused with a message, never samples with a zero
// normal (area sampling took the last face when every face weighed 0).
TEST(Samples, FacesWithoutANormalGiveNoSamples) {
  const TriangleMesh tiny({{0, 0, 0}, {1e-6, 0, 0}, {2e-6, 1e-21, 0}, {3e-6, 0, 1e-21}}, {{0, 1, 2}, {1, 3, 2}});
  ASSERT_GT(tiny.total_area(), 0);
  for (const char* spec : {"faces", "area:16"}) {
    try {
      const SampleSet samples = make_samples(tiny, parse_sample_spec(spec));
      for (const Vec3& n : samples.normals) EXPECT_NEAR(n.norm(), 1, 1e-12) << spec;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("no '"), std::string::npos) << e.what();
    }
  }
}

TEST(Statistics, HandComputedCase) {
  // d = {1, -2, 3} (hits) and one no-hit, h = 4: the no-hit counts as +4.
  const std::vector<double> d = {1, -2, 3, 0};
  const std::vector<std::uint8_t> hit = {1, 1, 1, 0};
  const std::vector<double> w = {1, 1, 2, 0};
  const Statistics s = compute_statistics(d, hit, w, 4.0, 8);
  EXPECT_EQ(s.no_hit_count, 1u);
  EXPECT_DOUBLE_EQ(s.siad, (1 - 2 + 3 + 4) / 4.0);
  EXPECT_DOUBLE_EQ(s.usiad, (1 + 2 + 3 + 4) / 4.0);
  EXPECT_DOUBLE_EQ(s.rms, std::sqrt((1 + 4 + 9 + 16) / 4.0));
  EXPECT_NEAR(s.std_signed, std::sqrt((1 + 4 + 9 + 16) / 4.0 - 1.5 * 1.5), 1e-12);
  EXPECT_DOUBLE_EQ(s.max_abs, 3);  // over the hits: the no-hit is counted apart, not folded in as h
  EXPECT_DOUBLE_EQ(s.min_signed, -2);
  EXPECT_DOUBLE_EQ(s.max_signed, 3);
  EXPECT_DOUBLE_EQ(s.siad_area, (1 - 2 + 6) / 4.0);  // the no-hit has weight 0 here
  EXPECT_DOUBLE_EQ(s.usiad_area, (1 + 2 + 6) / 4.0);
  EXPECT_DOUBLE_EQ(s.siad_hits, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.usiad_hits, 2.0);
  EXPECT_DOUBLE_EQ(s.p50, 2);  // nearest rank of {1, 2, 3, 4}
  EXPECT_DOUBLE_EQ(s.p99, 4);
  // Bins of width 1 over [-4, 4]: -2 in bin 2, 1 in bin 5, 3 in bin 7.
  EXPECT_EQ(s.histogram.counts, (std::vector<std::size_t>{0, 0, 1, 0, 0, 1, 0, 1}));
}

TEST(Statistics, EqualDistancesHaveZeroSpread) {
  // E[d^2] - E[d]^2 gave 1.3e-9 here; the spread of equal values is exactly 0.
  const std::vector<double> d(12, 0.1);
  const Statistics s = compute_statistics(d, std::vector<std::uint8_t>(12, 1), {}, 1.0);
  EXPECT_EQ(s.std_signed, 0.0);
  EXPECT_EQ(s.std_unsigned, 0.0);
  // A large offset with a small spread keeps its digits: {1e6 - 1, 1e6 + 1} has STD 1.
  const Statistics far = compute_statistics({1e6 - 1, 1e6 + 1}, {1, 1}, {}, 2e6);
  EXPECT_DOUBLE_EQ(far.std_signed, 1.0);
}

TEST(Statistics, PercentilesAreNearestRankOfTheSortedMagnitudes) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::vector<double> d(10007);
  for (double& x : d) x = uniform(random);
  const Statistics s = compute_statistics(d, std::vector<std::uint8_t>(d.size(), 1), {}, 1.0);
  std::vector<double> sorted(d.size());
  std::transform(d.begin(), d.end(), sorted.begin(), [](double x) { return std::abs(x); });
  std::sort(sorted.begin(), sorted.end());
  const auto rank = [&](double p) {
    return sorted[static_cast<std::size_t>(std::ceil(p / 100 * d.size())) - 1];
  };
  EXPECT_EQ(s.p50, rank(50));
  EXPECT_EQ(s.p90, rank(90));
  EXPECT_EQ(s.p95, rank(95));
  EXPECT_EQ(s.p99, rank(99));
}

// The hits' k-th |d| read past the no-hits (each kept as h): hits below h, equal to h and beyond it
// (closest point reports past h), at every rank.
TEST(Statistics, HitMagnitudesAreTheHitsOwnOrderStatistics) {
  const double h = 0.5;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::bernoulli_distribution missed(0.3), at_h(0.05);
  StatisticsAccumulator statistics(h);
  std::vector<double> hits;
  for (int k = 0; k < 2001; ++k) {
    const bool hit = !missed(random);
    const double d = at_h(random) ? -h : uniform(random);
    statistics.add(d, hit, 1.0);
    if (hit) hits.push_back(std::abs(d));
  }
  statistics.finish();
  std::sort(hits.begin(), hits.end());
  for (std::size_t k = 0; k < hits.size(); ++k) ASSERT_EQ(statistics.hit_magnitude(k), hits[k]) << "rank " << k;
  EXPECT_THROW(statistics.hit_magnitude(hits.size()), Error);
}

TEST(Statistics, RejectsEmptyAndMismatchedInput) {
  EXPECT_THROW(compute_statistics({}, {}, {}, 1.0), Error);
  EXPECT_THROW(compute_statistics({1.0}, {1, 1}, {}, 1.0), Error);
  EXPECT_THROW(compute_statistics({1.0}, {1}, {}, 0.0), Error);
  EXPECT_THROW(compute_statistics({1.0}, {1}, {}, std::nan("")), Error);
}

TEST(Orientation, ClosedOutwardInsideOutAndOpen) {
  const TriangleMesh outward = testing::box(1.0);
  const Orientation o = orientation(outward);
  EXPECT_TRUE(o.closed_and_consistent);
  EXPECT_NEAR(o.signed_volume, 8.0, 1e-12);
  std::vector<Triangle> flipped = outward.triangles().to_vector(), open = outward.triangles().to_vector();
  for (Triangle& t : flipped) std::swap(t[1], t[2]);
  const Orientation inside_out = orientation(TriangleMesh(outward.positions(), flipped));
  EXPECT_TRUE(inside_out.closed_and_consistent);
  EXPECT_NEAR(inside_out.signed_volume, -8.0, 1e-12);
  open.pop_back();  // a hole
  EXPECT_FALSE(orientation(TriangleMesh(outward.positions(), open)).closed_and_consistent);
  std::vector<Triangle> one_flipped = outward.triangles().to_vector();
  std::swap(one_flipped[3][1], one_flipped[3][2]);  // closed, but one face disagrees with its neighbours
  EXPECT_FALSE(orientation(TriangleMesh(outward.positions(), one_flipped)).closed_and_consistent);
  // The bunny has holes: no claim about its inside.
  EXPECT_FALSE(orientation(testing::bunny()).closed_and_consistent);
}

}  // namespace
}  // namespace roving

namespace {

// REF: the unit square at z = 0 (normal +z); TEST: the plane z = a x over a wider square. Along the
// normal d(x, y) = a x, so over REF the surface means are SiAD = USiAD = a / 2 and RMS = a / sqrt(3).
TEST(SamplingIntervals, CoverTheClosedFormSurfaceMeansNinetyFivePercentOfTheTime) {
  const double a = 0.1;
  const roving::TriangleMesh square({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 3, 2}});
  const roving::TriangleMesh tilted({{-1, -1, -a}, {2, -1, 2 * a}, {-1, 2, -a}, {2, 2, 2 * a}}, {{0, 1, 2}, {1, 3, 2}});
  const auto embree = roving::make_method("embree");
  embree->build(tilted);
  int covered[3] = {0, 0, 0};
  const int runs = 200;
  for (int seed = 1; seed <= runs; ++seed) {
    const roving::SampleSet samples =
        roving::make_samples(square, {roving::SampleSpec::Kind::Area, 500, static_cast<std::uint64_t>(seed)});
    const roving::DistanceResult r = embree->measure(samples, {roving::Semantics::FirstHit, 0.5});
    const roving::SamplingIntervals i = roving::sampling_intervals(r.signed_distance, r.hit, 0.5);
    covered[0] += i.siad.lower <= a / 2 && a / 2 <= i.siad.upper;
    covered[1] += i.usiad.lower <= a / 2 && a / 2 <= i.usiad.upper;
    covered[2] += i.rms.lower <= a / std::sqrt(3.0) && a / std::sqrt(3.0) <= i.rms.upper;
    EXPECT_NEAR(i.siad.standard_error, a / std::sqrt(12.0) / std::sqrt(500.0), 0.1 * a / std::sqrt(12.0 * 500));
  }
  // 95% of 200: 190, with a binomial standard deviation of 3.1; [180, 199] is about +-3 of them.
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(covered[k], 180) << "statistic " << k;
    EXPECT_LE(covered[k], 199) << "statistic " << k;
  }
}

TEST(SamplingIntervals, RefuseTooFewSamples) {
  EXPECT_THROW(roving::sampling_intervals({1.0}, {1}, 1.0), roving::Error);
  EXPECT_THROW(roving::sampling_intervals({1.0, 2.0}, {1}, 1.0), roving::Error);
}

// The radix sort is std::stable_sort's order, on 128- and 64-bit keys: keys from each of the 16 bytes (some bytes constant,
// as a voxelised cloud's low mantissa bytes are), many ties, sizes across its chunks of 2^16.
TEST(RadixSort, OrdersAsAStableSortDoes) {
  std::mt19937_64 random(7);
  for (const std::size_t n : {0, 1, 2, 1000, 65536, 200001}) {
    struct Item {
      roving::RadixKey key;
      std::size_t index;
    };
    std::vector<Item> items(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bits = random();
      // Few distinct values, spread over the high and low words, byte 2 of each word always 0x5a.
      const std::uint64_t low = (bits % 37) * 0x0101010101000001ull | 0x5a0000ull;
      const std::uint64_t high = (bits >> 32) % 11 * 0x0100000000000100ull | 0x5a0000ull;
      items[i] = {roving::RadixKey(high) << 64 | low, i};
    }
    std::vector<Item> expected = items;
    std::stable_sort(expected.begin(), expected.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
    roving::radix_sort(items, [](const Item& item) { return item.key; });
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(items[i].index, expected[i].index) << "n " << n << ", place " << i;
    }
    // The same keys' low words as 64-bit keys (their digits picked out of a word, not two).
    std::vector<Item> low = expected;
    std::shuffle(low.begin(), low.end(), random);
    std::vector<Item> low_expected = low;
    const auto low_word = [](const Item& item) { return std::uint64_t(item.key); };
    std::stable_sort(low_expected.begin(), low_expected.end(),
                     [&](const Item& a, const Item& b) { return low_word(a) < low_word(b); });
    roving::radix_sort(low, low_word);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(low[i].index, low_expected[i].index) << "64-bit keys, n " << n << ", place " << i;
    }
  }
}

}  // namespace

// Mt19937_64 draws what std::mt19937_64 draws (the standard fixes every value), before and after a
// discard of any length: within the block held, by steps (below 2^20) and by a jump.
TEST(MersenneTwister, DrawsAndDiscardsAsTheStandardEngine) {
  for (const std::uint64_t seed : {5489ull, 1ull, 20261128ull}) {
    roving::Mt19937_64 ours(seed);
    std::mt19937_64 standard(seed);
    for (const unsigned long long count : {0ull, 1ull, 5ull, 311ull, 312ull, 313ull, 1000ull, (1ull << 20) - 1,
                                           1ull << 20, 12345677ull, 100000003ull}) {
      ours.discard(count);
      standard.discard(count);
      for (int i = 0; i < 700; ++i) ASSERT_EQ(ours(), standard()) << "seed " << seed << ", after " << count;
    }
  }
  // 3 x 10^9 on (a shard's first sample near the billionth): std::mt19937_64 (GCC 12's libstdc++)
  // took 16 s to discard as many and then drew this.
  roving::Mt19937_64 far(1);
  far.discard(3000000000ull);
  EXPECT_EQ(far(), 3426357536092157650ull);
}
