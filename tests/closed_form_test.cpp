// Closed-form cases run through every CPU method: identical models, a box against the same box
// scaled about its centre, a view volume with no surface in it, lines through vertices and edges.
#include <gtest/gtest.h>

#include "roving/core/statistics.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

using testing::box;

// Coordinates are O(1) and every method computes in double (Embree in float, then re-intersects
// the hit triangle's plane in double): 1e-9 is far above rounding and far below any offset tested.
constexpr double kExact = 1e-9;

struct Case {
  std::string method;
  Semantics semantics;
};

// Every CPU method and semantics but vertex-to-vertex, whose nearest vertex is not a point of
// the surface (it has its own test below). The GL methods, float-precise, have gl_methods_test.
std::vector<Case> surface_cases() {
  std::vector<Case> cases;
  for (const auto& name : method_names()) {
    if (name.rfind("v2v", 0) == 0 || is_gl_method(name)) continue;
    for (Semantics s : make_method(name)->supported_semantics()) cases.push_back({name, s});
  }
  return cases;
}

class SurfaceMethods : public ::testing::TestWithParam<Case> {
 protected:
  DistanceResult run(const TriangleMesh& reference, const TriangleMesh& test, SampleSpec spec, double h) {
    auto method = make_method(GetParam().method);
    const SampleSet samples = make_samples(reference, spec);
    return measure_distances(*method, test, samples, {GetParam().semantics, h});
  }
};

TEST_P(SurfaceMethods, IdenticalModelsGiveZeroEverywhere) {
  const TriangleMesh cube = box(1.0);
  const DistanceResult result = run(cube, cube, {SampleSpec::Kind::Area, 500}, 0.5);
  for (std::size_t k = 0; k < result.hit.size(); ++k) {
    ASSERT_TRUE(result.hit[k]) << "sample " << k;
    EXPECT_NEAR(result.signed_distance[k], 0.0, kExact);
  }
}

TEST_P(SurfaceMethods, ScaledBoxGivesTheExactOffsetWithItsSign) {
  const TriangleMesh cube = box(1.0);
  for (double scale : {1.1, 0.9}) {
    const DistanceResult result = run(cube, box(scale), {}, 0.5);
    const double expected = scale - 1.0;  // outside (+) when the test box is larger
    for (std::size_t k = 0; k < result.hit.size(); ++k) {
      ASSERT_TRUE(result.hit[k]) << "face sample " << k << ", scale " << scale;
      EXPECT_NEAR(result.signed_distance[k], expected, kExact) << "face sample " << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(CpuMethods, SurfaceMethods, ::testing::ValuesIn(surface_cases()),
                         [](const auto& info) {
                           std::string name = info.param.method + "_" + to_string(info.param.semantics);
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

TEST(VertexToVertex, ModelAgainstItselfFromItsVerticesIsZero) {
  const TriangleMesh cube = box(1.0);
  const SampleSet samples = make_samples(cube, {SampleSpec::Kind::Vertices});
  for (const char* name : {"v2v-naive", "v2v-kdtree"}) {
    auto method = make_method(name);
    const auto result = measure_distances(*method, cube, samples, {Semantics::Closest, 0.5});
    for (double d : result.signed_distance) EXPECT_EQ(d, 0.0) << name;
  }
}

class RayMethods : public ::testing::TestWithParam<std::string> {};

TEST_P(RayMethods, EmptyViewVolumeIsANoHitCountedAsMaxError) {
  // Test box far smaller than the reference box: nothing within h = 0.2 of the reference faces.
  const TriangleMesh cube = box(1.0);
  auto method = make_method(GetParam());
  const SampleSet samples = make_samples(cube, {});
  const double h = 0.2;
  for (Semantics s : {Semantics::FirstHit, Semantics::Nearest}) {
    const DistanceResult result = measure_distances(*method, box(0.5), samples, {s, h});
    EXPECT_EQ(result.hit_count(), 0u);
    const Statistics stats = compute_statistics(result.signed_distance, result.hit, samples.weights, h);
    EXPECT_EQ(stats.no_hit_count, samples.size());
    EXPECT_DOUBLE_EQ(stats.usiad, h);
    EXPECT_DOUBLE_EQ(stats.max_abs, 0);  // nothing hit: no extreme to report
  }
}

TEST_P(RayMethods, FirstHitSeesTheNearerLayerNearestSeesTheCloserOne) {
  // Two parallel planes (z = +0.3 and z = -0.1) against samples on z = 0 with normal +z, h = 0.5:
  // first-hit meets z = +0.3 first (d = +0.3), nearest-on-line takes z = -0.1 (d = -0.1).
  const std::vector<Vec3> p = {{-2, -2, 0.3},  {2, -2, 0.3},  {2, 2, 0.3},  {-2, 2, 0.3},
                               {-2, -2, -0.1}, {2, -2, -0.1}, {2, 2, -0.1}, {-2, 2, -0.1}};
  const TriangleMesh planes(p, {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}});
  const TriangleMesh reference({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  auto method = make_method(GetParam());
  const SampleSet samples = make_samples(reference, {SampleSpec::Kind::Area, 200});
  const auto first = measure_distances(*method, planes, samples, {Semantics::FirstHit, 0.5});
  const auto nearest = measure_distances(*method, planes, samples, {Semantics::Nearest, 0.5});
  for (std::size_t k = 0; k < samples.size(); ++k) {
    ASSERT_TRUE(first.hit[k] && nearest.hit[k]);
    EXPECT_NEAR(first.signed_distance[k], 0.3, kExact);
    EXPECT_NEAR(nearest.signed_distance[k], -0.1, kExact);
  }
}

TEST_P(RayMethods, LinesThroughVerticesAndEdgesAreNeverLost) {
  // A 20 x 20 grid of unit squares split into triangles in z = 0, measured against itself from
  // its own vertices and edge midpoints: every line crosses the surface exactly at a vertex or
  // on an edge shared by two triangles, where a non-watertight test can slip through.
  const int n = 20;
  std::vector<Vec3> p;
  std::vector<Triangle> t;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) p.emplace_back(i * 0.1, j * 0.1, 0.0);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  }
  const TriangleMesh grid(p, t);
  SampleSet samples;
  for (int j = 1; j < n; ++j) {
    for (int i = 1; i < n; ++i) {
      for (const Vec3& x : {Vec3(i * 0.1, j * 0.1, 0), Vec3(i * 0.1 + 0.05, j * 0.1, 0),
                            Vec3(i * 0.1, j * 0.1 + 0.05, 0), Vec3(i * 0.1 + 0.05, j * 0.1 + 0.05, 0)}) {
        samples.positions.push_back(x);
        samples.normals.push_back(Vec3::UnitZ());
        samples.weights.push_back(1);
      }
    }
  }
  auto method = make_method(GetParam());
  for (Semantics s : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
    const auto result = measure_distances(*method, grid, samples, {s, 0.05});
    for (std::size_t k = 0; k < samples.size(); ++k) {
      ASSERT_TRUE(result.hit[k]) << to_string(s) << ": line through " << samples.positions[k].transpose()
                                 << " lost";
      EXPECT_NEAR(result.signed_distance[k], 0.0, kExact);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(References, RayMethods, ::testing::Values("embree", "cgal"));

}  // namespace
}  // namespace roving
