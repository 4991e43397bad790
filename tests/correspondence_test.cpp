// Each sample's point on TEST and its barycentric coordinates (correspondence.h), from the exact
// methods and the baselines, against what the distance itself says: the point lies on the face the
// method names, at the distance it reported.
#include "roving/core/correspondence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "analytic.h"
#include "roving/core/normal_line.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

struct Case {
  const char* method;
  Semantics semantics;
};

TEST(Correspondences, LieOnTheNamedFaceAtTheReportedDistance) {
  const TriangleMesh& reference = testing::bunny();
  const double diagonal = reference.bounding_box().diagonal();
  const TriangleMesh test = smoothly_perturbed(reference, 0.01 * diagonal, 0.2 * diagonal);
  const SampleSet samples = make_samples(reference, parse_sample_spec("area:4000"));
  // Rounding of coordinates of size ~diagonal through a few dozen operations.
  const double rounding = 1e-12 * diagonal;
  // The normal line meets a triangle widened by this much across the line, its crossing then
  // clamped into [-h, h] by at most as much (normal_line.h): x + d n is that far from the face.
  const double widening = kNormalLineTolerance * test.bounding_box().diagonal();
  for (const Case& c : {Case{"embree", Semantics::FirstHit}, Case{"embree", Semantics::Nearest},
                        Case{"embree", Semantics::Closest}, Case{"cgal", Semantics::FirstHit},
                        Case{"cgal", Semantics::Closest}, Case{"v2p-aabb", Semantics::Closest}, Case{"v2p-naive", Semantics::Closest}}) {
    SCOPED_TRACE(std::string(c.method) + " " + to_string(c.semantics));
    DistanceOptions options{c.semantics, 0.05 * diagonal};
    options.faces = true;
    auto method = make_method(c.method);
    const DistanceResult result = measure_distances(*method, test, samples, options);
    ASSERT_EQ(result.hit_face.size(), samples.size());
    const Correspondences found = correspondences(samples, test, result, c.semantics);
    std::size_t hits = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (!result.hit[k]) {
        EXPECT_TRUE(found.points[k].array().isNaN().all());
        EXPECT_TRUE(found.barycentric[k].array().isNaN().all());
        continue;
      }
      ++hits;
      const Vec3& x = samples.positions[k];
      const Vec3& point = found.points[k];
      const Vec3& w = found.barycentric[k];
      const Triangle& t = test.triangles()[result.hit_face[k]];
      const auto& p = test.positions();
      // Barycentric coordinates of the named face that give the point.
      ASSERT_GE(w.minCoeff(), 0) << "sample " << k;
      ASSERT_NEAR(w.sum(), 1, 1e-12) << "sample " << k;
      ASSERT_LE((w[0] * p[t[0]] + w[1] * p[t[1]] + w[2] * p[t[2]] - point).norm(), rounding) << "sample " << k;
      if (c.semantics == Semantics::Closest) {
        // The closest point: exactly |d| from the sample, on d's side of it.
        ASSERT_NEAR((point - x).norm(), std::abs(result.signed_distance[k]), rounding) << "sample " << k;
        ASSERT_GE((point - x).dot(samples.normals[k]) * result.signed_distance[k], -rounding * rounding);
      } else {
        // Where the normal line meets the face: at x + d n, to the rule's widening.
        const Vec3 on_line = x + result.signed_distance[k] * samples.normals[k];
        ASSERT_LE((point - on_line).norm(), 2 * widening + rounding) << "sample " << k;
      }
    }
    EXPECT_GT(hits, samples.size() * 9 / 10);
  }
}

TEST(Correspondences, WithoutTheFaceOnlyTheLinesPointIsKnown) {
  const TriangleMesh& reference = testing::bunny();
  const double diagonal = reference.bounding_box().diagonal();
  const TriangleMesh test = smoothly_perturbed(reference, 0.01 * diagonal, 0.2 * diagonal);
  const SampleSet samples = make_samples(reference, parse_sample_spec("area:500"));
  auto method = make_method("embree");
  DistanceResult line = measure_distances(*method, test, samples, {Semantics::FirstHit, 0.05 * diagonal});
  ASSERT_TRUE(line.hit_face.empty());  // not asked for
  const Correspondences on_line = correspondences(samples, test, line, Semantics::FirstHit);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EXPECT_TRUE(on_line.barycentric[k].array().isNaN().all());
    if (line.hit[k]) {
      EXPECT_EQ(on_line.points[k], Vec3(samples.positions[k] + line.signed_distance[k] * samples.normals[k]));
    }
  }
  // The nearest-vertex baseline names a vertex, not a face: no face, and so no closest point.
  DistanceOptions options{Semantics::Closest, 0.05 * diagonal};
  options.faces = true;
  auto vertices = make_method("v2v-kdtree");
  const DistanceResult nearest = measure_distances(*vertices, test, samples, options);
  EXPECT_TRUE(nearest.hit_face.empty());
  const Correspondences none = correspondences(samples, test, nearest, Semantics::Closest);
  for (std::size_t k = 0; k < samples.size(); ++k) EXPECT_TRUE(none.points[k].array().isNaN().all());
}

}  // namespace
}  // namespace roving
