// Exact means exact: Embree, CGAL and GL roving implement one first-hit rule (normal_line.h),
// so a model against itself has no no-hit and the same d from every exact method on every
// sample, and lines through test vertices get the same hit flag from all three.
#include <gtest/gtest.h>

#include <cctype>

#include "analytic.h"
#include "roving/core/error.h"
#include "roving/core/normal_line.h"
#include "roving/gl_methods/agreement.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/model.h"
#include "roving/representations/voxel_surface.h"
#include "test_support.h"
#include "voxelize.h"

namespace roving {
namespace {

TEST(NormalLine, ClosedTrianglesWidenedByTheTolerance) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const auto s_of = [&](const Vec3& x, double tolerance) {
    const auto crossing = NormalLine(x, Vec3(0, 0, 1), 1.0, tolerance).crossing(a, b, c);
    return crossing ? std::optional<double>(crossing->high) : std::nullopt;
  };
  EXPECT_DOUBLE_EQ(*s_of({0.2, 0.2, 0.5}, 0), -0.5);  // through the interior: d = -0.5
  EXPECT_TRUE(s_of({0, 0, 0}, 0));                    // through a vertex, no tolerance
  EXPECT_TRUE(s_of({0.5, 0, 0}, 0));                  // along an edge
  EXPECT_TRUE(s_of({0.5, 0.5, 0}, 0));                // through the hypotenuse
  EXPECT_FALSE(s_of({-1e-9, 0.5, 0}, 0));             // just outside
  EXPECT_TRUE(s_of({-1e-9, 0.5, 0}, 2e-9));           // within the tolerance
  EXPECT_FALSE(s_of({-3e-9, 0.5, 0}, 2e-9));
  EXPECT_FALSE(s_of({0.2, 0.2, 1.5}, 0));  // beyond h
  // Edge-on: the line in the triangle's plane meets it over an interval of s.
  const auto edge_on =
      NormalLine({0.25, 0, 0.5}, Vec3(0, 1, 0), 2.0, 1e-9).crossing({0, 0, 0.5}, {1, 0, 0.5}, {0, 1, 0.5});
  ASSERT_TRUE(edge_on);
  EXPECT_NEAR(edge_on->low, 0, 1e-15);
  EXPECT_NEAR(edge_on->high, 0.75, 1e-15);
}

// The rule's quick rejection of triangles wholly to one side of the line or beyond the view
// volume must keep those at exactly the tolerance: across the line and past either end.
TEST(NormalLine, QuickRejectionKeepsTrianglesAtTheTolerance) {
  const double tolerance = 1e-6;
  const NormalLine line(Vec3(0, 0, 0), Vec3(0, 0, 1), 1.0, tolerance);
  // Wholly beside the line (u or v of every corner >= the tolerance), nearest at exactly it.
  for (const double side : {tolerance, -tolerance}) {
    const double far = side > 0 ? 1 : -1;
    const auto beside_x = line.crossing({side, -1, 0.3}, {side, 1, 0.3}, {far, 0, 0.3});
    const auto beside_y = line.crossing({-1, side, 0.3}, {1, side, 0.3}, {0, far, 0.3});
    ASSERT_TRUE(beside_x && beside_y) << side;
    EXPECT_EQ(beside_x->high, 0.3);
    EXPECT_EQ(beside_y->high, 0.3);
  }
  // Wholly past an end of the view volume by the tolerance: met, and clamped to the end.
  const auto above = line.crossing({-1, -1, 1 + tolerance}, {1, -1, 1 + tolerance}, {0, 1, 1 + tolerance});
  const auto below = line.crossing({-1, -1, -1 - tolerance}, {1, -1, -1 - tolerance}, {0, 1, -1 - tolerance});
  ASSERT_TRUE(above && below);
  EXPECT_EQ(above->high, 1.0);
  EXPECT_EQ(below->low, -1.0);
  // A little farther, not met.
  EXPECT_FALSE(line.crossing({2 * tolerance, 0, 0.3}, {2 * tolerance, 1, 0.3}, {1, 0.5, 0.3}));
  EXPECT_FALSE(line.crossing({-1, -1, 1.01}, {1, -1, 1.01}, {0, 1, 1.01}));
}

TEST(NormalLine, NearestPrefersTheOuterOfTwoEquallyNearCrossings) {
  for (bool reversed : {false, true}) {
    CrossingChoice choice(Semantics::Nearest, 1.0);
    choice.consider({reversed ? 0.1 : -0.1, reversed ? 0.1 : -0.1}, 0);
    choice.consider({reversed ? -0.1 : 0.1, reversed ? -0.1 : 0.1}, 1);
    EXPECT_EQ(*choice.chosen(), 0.1);
  }
}

// Once the chosen d cannot be bettered (0 for nearest, h for first-hit, where crossings are
// clamped), only a lower face can change the choice: settled_for says so, and it is true, for
// every value and sign a higher face's crossing might bring.
TEST(NormalLine, ASettledChoiceIsOnlyChangedByALowerFace) {
  const double h = 0.5;
  for (const Semantics semantics : {Semantics::Nearest, Semantics::FirstHit}) {
    const double best = semantics == Semantics::Nearest ? 0.0 : h;
    CrossingChoice choice(semantics, h);
    EXPECT_FALSE(choice.settled_for(7));
    choice.consider({0.25, 0.25}, 9);
    EXPECT_FALSE(choice.settled_for(12)) << "d = 0.25 can still be bettered";
    choice.consider({best, best}, 7);
    EXPECT_TRUE(choice.settled_for(8));
    EXPECT_FALSE(choice.settled_for(7));
    EXPECT_FALSE(choice.settled_for(3));
    for (const double d : {-h, -0.0, 0.0, 0.1, h}) {
      CrossingChoice higher = choice;
      higher.consider({d, d}, 8);
      EXPECT_EQ(higher.chosen_hit()->face, 7u);
      EXPECT_EQ(std::signbit(*higher.chosen()), std::signbit(best));
      EXPECT_EQ(*higher.chosen(), best);
    }
    CrossingChoice lower = choice;
    lower.consider({best, best}, 3);
    EXPECT_EQ(lower.chosen_hit()->face, 3u);
  }
}

// Every real model against itself: no no-hit, and Embree and CGAL give the same d on every
// sample under every semantics; GL roving the same flags and d within its depth tolerance.
class EveryModel : public ::testing::TestWithParam<const char*> {};

Model model_named(const std::string& name) {
  if (name != "bunny voxels 48^3") return load_model(testing::data_file(name));
  Model voxels;
  voxels.type = ModelType::Voxels;
  voxels.voxels = voxelize_thin(testing::bunny(), 48);
  voxels.mesh.mesh = exposed_faces(*voxels.voxels);
  return voxels;
}

TEST_P(EveryModel, AgainstItselfHasNoNoHitAndOneAnswer) {
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const auto embree = make_method("embree"), cgal = make_method("cgal"), roving = make_method("roving");
  const std::string name = GetParam();
  const Model model = model_named(name);
  const TriangleMesh& surface = test_surface(model);
  embree->build(surface);
  cgal->build(surface);
  roving->build(surface);
  const double h = 0.05 * model.bounding_box().diagonal();
  // Under the sanitizers 2,000 of each kind's samples, spread over the model (the Release suite
  // takes them all).
  for (const char* kind : {"faces", "vertices", "area:20000"}) {
    if (model.type == ModelType::Voxels && std::string(kind) == "vertices") continue;
    const SampleSet samples = testing::lighter_under_sanitizers(reference_samples(model, parse_sample_spec(kind)), 2000);
    for (Semantics semantics : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
      const DistanceOptions options{semantics, h};
      const DistanceResult e = embree->measure(samples, options), g = cgal->measure(samples, options);
      EXPECT_EQ(e.hit_count(), samples.size()) << name << " " << kind << " " << to_string(semantics);
      std::size_t differ = 0;
      for (std::size_t k = 0; k < samples.size(); ++k) {
        differ += e.hit[k] != g.hit[k] || (e.hit[k] && e.signed_distance[k] != g.signed_distance[k]);
      }
      // Closest-point distances come from two different searches: equal to rounding.
      if (semantics == Semantics::Closest) {
        EXPECT_EQ(agreement(e, g, 1e-12 * h).close_fraction(), 1.0) << name << " " << kind;
      } else {
        EXPECT_EQ(differ, 0u) << name << " " << kind << " " << to_string(semantics);
      }
      if (semantics == Semantics::FirstHit) {
        const DistanceResult r = roving->measure(samples, options);
        EXPECT_EQ(r.hit_count(), samples.size()) << name << " " << kind << " roving";
        const Agreement a = agreement(e, r, roving_tolerance(*r.gl));
        EXPECT_EQ(a.same_flag, a.samples) << name << " " << kind << " roving";
        // The depth tolerance assumes surfaces within 84 degrees of facing the camera;
        // steeper ones are the 0.5% that roving's own gate leaves.
        EXPECT_GE(a.close_fraction(), 0.995) << name << " " << kind << " roving";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(RealModels, EveryModel,
                         ::testing::Values("stanford-bunny.obj", "rocker-arm.obj", "rocker-arm-80k.ply",
                                           "fandisk.obj", "igea.ply", "teapot.bpt", "bunny voxels 48^3"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

// Vertex samples against a copy whose vertices moved along their normals by a smooth field:
// every normal line passes through a test vertex (up to rounding). The three exact methods
// give the same hit flag on >= 99.99% of samples.
TEST(Exactness, LinesThroughTestVerticesGetOneHitFlag) {
  const auto embree = make_method("embree"), cgal = make_method("cgal");
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const auto roving = make_method("roving");
  for (const char* file : {"fandisk.obj", "stanford-bunny.obj", "rocker-arm.obj"}) {
    const TriangleMesh reference = load_mesh(testing::data_file(file)).mesh;
    const double diagonal = reference.bounding_box().diagonal();
    for (double amplitude : {0.01, 0.002}) {
      const TriangleMesh test = smoothly_perturbed(reference, amplitude * diagonal, 0.2 * diagonal);
      // Under the sanitizers 4,000 of them, spread over the model (the Release suite takes all).
      const SampleSet samples = testing::lighter_under_sanitizers(make_samples(reference, parse_sample_spec("vertices")), 4000);
      const DistanceOptions options{Semantics::FirstHit, 0.02 * diagonal};
      embree->build(test);
      cgal->build(test);
      const DistanceResult e = embree->measure(samples, options), g = cgal->measure(samples, options);
      const Agreement cpu = agreement(e, g, 0.0);
      EXPECT_EQ(cpu.same_flag, cpu.samples) << file << " " << amplitude;
      EXPECT_EQ(cpu.close, cpu.common_hits) << file << " " << amplitude;
      {
        roving->build(test);
        const DistanceResult r = roving->measure(samples, options);
        const Agreement gl = agreement(e, r, roving_tolerance(*r.gl));
        EXPECT_GE(gl.same_flag_fraction(), 0.9999)
            << file << " " << amplitude << ": " << gl.samples - gl.same_flag << " of " << gl.samples
            << " differ";
      }
    }
  }
}

}  // namespace
}  // namespace roving
