// CGAL and Embree, two independent exact references, agree on the bunny against a smoothly
// perturbed copy of itself, for each semantics; the naive and accelerated baselines agree exactly.
#include <gtest/gtest.h>

#include "analytic.h"
#include "roving/reference_cgal/cgal_reference.h"
#include "roving/reference_embree/embree_reference.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

struct Agreement {
  std::size_t samples = 0, same_flag = 0, common_hits = 0, close = 0;
};

Agreement compare(const DistanceResult& a, const DistanceResult& b, double tolerance) {
  Agreement agreement;
  agreement.samples = a.hit.size();
  for (std::size_t k = 0; k < a.hit.size(); ++k) {
    agreement.same_flag += a.hit[k] == b.hit[k];
    if (a.hit[k] && b.hit[k]) {
      ++agreement.common_hits;
      agreement.close += std::abs(a.signed_distance[k] - b.signed_distance[k]) <= tolerance;
    }
  }
  return agreement;
}

class BunnyAgainstPerturbedCopy : public ::testing::TestWithParam<Semantics> {
 protected:
  static void SetUpTestSuite() {
    const TriangleMesh& bunny = testing::bunny();
    diagonal_ = bunny.bounding_box().diagonal();
    // 1% of the diagonal in amplitude, waves a fifth of the diagonal long.
    test_ = new TriangleMesh(smoothly_perturbed(bunny, 0.01 * diagonal_, 0.2 * diagonal_));
    samples_ = new SampleSet(make_samples(bunny, {}));
  }
  static void TearDownTestSuite() {
    delete test_;
    delete samples_;
  }
  static inline double diagonal_ = 0;
  static inline TriangleMesh* test_ = nullptr;
  static inline SampleSet* samples_ = nullptr;
};

TEST_P(BunnyAgainstPerturbedCopy, CgalAndEmbreeAgree) {
  const DistanceOptions options{GetParam(), 0.05 * diagonal_};
  auto embree = make_method("embree");
  auto cgal = make_method("cgal");
  const DistanceResult e = measure_distances(*embree, *test_, *samples_, options);
  const DistanceResult c = measure_distances(*cgal, *test_, *samples_, options);
  ASSERT_EQ(samples_->size(), 69451u);
  // Tolerance: 1e-5 of the diagonal, the bar; both compute the hit in double against the
  // same triangle's plane, so they differ by rounding unless they pick different triangles.
  const Agreement a = compare(e, c, 1e-5 * diagonal_);
  EXPECT_GE(a.same_flag, 0.999 * a.samples) << a.samples - a.same_flag << " flags differ";
  EXPECT_GE(a.close, 0.9999 * a.common_hits) << a.common_hits - a.close << " distances differ";
  // The perturbation reaches ~1% of the diagonal, so most samples see a non-zero distance.
  EXPECT_GT(e.hit_count(), 0.99 * a.samples);
}

INSTANTIATE_TEST_SUITE_P(EachSemantics, BunnyAgainstPerturbedCopy,
                         ::testing::Values(Semantics::FirstHit, Semantics::Nearest, Semantics::Closest),
                         [](const auto& info) {
                           std::string name = to_string(info.param);
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

// The libraries' own queries (roving-bench's raw limits) answer the same questions: on the
// bunny against its perturbed copy they agree with the exact references wherever the rule's
// tolerance does not decide (the same bar as Embree's and CGAL's agreement above).
TEST(RawQueries, AgreeWithTheExactReferences) {
  const TriangleMesh& bunny = testing::bunny();
  const double diagonal = bunny.bounding_box().diagonal(), h = 0.05 * diagonal;
  const TriangleMesh test = smoothly_perturbed(bunny, 0.01 * diagonal, 0.2 * diagonal);
  const SampleSet samples = make_samples(bunny, {SampleSpec::Kind::Area, 5000});
  for (const Semantics semantics : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
    auto embree = make_method("embree");
    const DistanceResult exact = measure_distances(*embree, test, samples, {semantics, h});
    for (const RawRun& raw :
         {raw_embree_queries(test, samples, semantics, h), raw_cgal_queries(test, samples, semantics, h)}) {
      ASSERT_EQ(raw.distance.size(), samples.size());
      std::size_t same_flag = 0, common = 0, close = 0;
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const bool raw_hit = !std::isnan(raw.distance[k]);
        same_flag += raw_hit == bool(exact.hit[k]);
        if (!raw_hit || !exact.hit[k]) continue;
        ++common;
        const double d =
            semantics == Semantics::Closest ? std::abs(exact.signed_distance[k]) : exact.signed_distance[k];
        close += std::abs(d - raw.distance[k]) <= 1e-5 * diagonal;
      }
      EXPECT_GE(same_flag, 0.999 * samples.size()) << to_string(semantics);
      EXPECT_GE(close, 0.9999 * common) << to_string(semantics);
      EXPECT_GT(raw.query_seconds, 0.0);
    }
  }
}

TEST(Baselines, NaiveAndAcceleratedAgreeOnTheBunny) {
  const TriangleMesh& bunny = testing::bunny();
  const double diagonal = bunny.bounding_box().diagonal();
  const TriangleMesh test = smoothly_perturbed(bunny, 0.01 * diagonal, 0.2 * diagonal);
  // A subset keeps the brute force short (2,000 x 69,451 triangles).
  const SampleSet samples = make_samples(bunny, {SampleSpec::Kind::Area, 2000});
  const DistanceOptions options{Semantics::Closest, 0.05 * diagonal};
  for (const auto& [naive, accelerated] :
       {std::pair{"v2v-naive", "v2v-kdtree"}, std::pair{"v2p-naive", "v2p-aabb"}}) {
    auto a = make_method(naive);
    auto b = make_method(accelerated);
    const auto ra = measure_distances(*a, test, samples, options);
    const auto rb = measure_distances(*b, test, samples, options);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      // Same nearest element, so the same double computation up to the order of operations.
      ASSERT_NEAR(ra.signed_distance[k], rb.signed_distance[k], 1e-12 * diagonal) << naive << " sample " << k;
    }
  }
}

TEST(Baselines, VertexToPlaneMatchesTheClosestPointReferences) {
  const TriangleMesh& bunny = testing::bunny();
  const double diagonal = bunny.bounding_box().diagonal();
  const TriangleMesh test = smoothly_perturbed(bunny, 0.01 * diagonal, 0.2 * diagonal);
  const DistanceOptions options{Semantics::Closest, 0.05 * diagonal};
  auto v2p = make_method("v2p-naive");
  auto embree = make_method("embree");
  // Scattered samples, and neighbouring ones in mesh order, where Embree starts each search from
  // the previous sample's closest point.
  for (const SampleSet& samples :
       {make_samples(bunny, {SampleSpec::Kind::Area, 2000}), make_samples(bunny, {}).head(2000)}) {
    const auto a = measure_distances(*v2p, test, samples, options);
    const auto b = measure_distances(*embree, test, samples, options);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      ASSERT_NEAR(a.signed_distance[k], b.signed_distance[k], 1e-9 * diagonal) << samples.kind << " sample " << k;
    }
  }
}

}  // namespace
}  // namespace roving
