// The colour rule (README "Colour"): the colour science against published figures, closed-form
// colour differences on planes whose colours are a known linear field, and Embree and CGAL giving
// the same faces and colours sample by sample.
#include "roving/core/colour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "analytic.h"
#include "colour_models.h"
#include "coloured.h"
#include "roving/core/colour_science.h"
#include "roving/core/colour_statistics.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

using testing::gradient_plane;

// Sharma, Wu and Dalal (2005), Table 1: the 34 CIELAB pairs and their CIEDE2000 differences.
struct SharmaPair {
  Vec3 lab1, lab2;
  double delta_e;
};
const SharmaPair kSharma[] = {
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {{50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0012, -2.4900}, 4.7461},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {{61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {{35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {{36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

TEST(ColourScience, Ciede2000MatchesSharmasTable) {
  for (std::size_t i = 0; i < std::size(kSharma); ++i) {
    const SharmaPair& p = kSharma[i];
    // The table gives four decimals: half a unit of the last is its rounding.
    EXPECT_NEAR(ciede2000(p.lab1, p.lab2), p.delta_e, 0.5e-4) << "pair " << i + 1;
    EXPECT_EQ(ciede2000(p.lab1, p.lab2), ciede2000(p.lab1, p.lab2));
  }
  EXPECT_EQ(ciede2000(Vec3(40, 10, -20), Vec3(40, 10, -20)), 0.0);
}

TEST(ColourScience, SrgbPrimariesInLab) {
  // sRGB white is the white point; greys have no chroma; red, green and blue as IEC 61966-2-1's
  // primaries give them (two decimals, as commonly tabulated).
  const Vec3 white = srgb_to_lab(Vec3(255, 255, 255));
  EXPECT_NEAR(white.x(), 100, 1e-9);
  EXPECT_NEAR(white.y(), 0, 1e-9);
  EXPECT_NEAR(white.z(), 0, 1e-9);
  EXPECT_NEAR(srgb_to_lab(Vec3(0, 0, 0)).x(), 0, 1e-12);
  for (double grey : {1.0, 10.0, 128.0, 200.0}) {
    EXPECT_NEAR(srgb_to_lab(Vec3(grey, grey, grey)).tail<2>().norm(), 0, 1e-9);
  }
  const std::array<std::pair<Vec3, Vec3>, 3> primaries = {{{{255, 0, 0}, {53.24, 80.09, 67.20}},
                                                           {{0, 255, 0}, {87.73, -86.18, 83.18}},
                                                           {{0, 0, 255}, {32.30, 79.19, -107.86}}}};
  for (const auto& [rgb, lab] : primaries) EXPECT_LT((srgb_to_lab(rgb) - lab).cwiseAbs().maxCoeff(), 0.01);
}

TEST(ColourScience, YcbcrBt709) {
  const Vec3 white = ycbcr_bt709(Vec3(255, 255, 255));
  EXPECT_NEAR(white.x(), 255, 1e-12);
  EXPECT_NEAR(white.y(), 0, 1e-12);
  EXPECT_NEAR(white.z(), 0, 1e-12);
  // Pure blue and red reach Cb and Cr's extremes: half the range.
  EXPECT_NEAR(ycbcr_bt709(Vec3(0, 0, 255)).y(), 127.5, 1e-12);
  EXPECT_NEAR(ycbcr_bt709(Vec3(255, 0, 0)).z(), 127.5, 1e-12);
}

TEST(ColourStatistics, PsnrAndMeansOfAKnownDifference) {
  // Every hit's R' off by 10 (G', B' equal); a no-hit is left out.
  ColourPairs pairs;
  const std::vector<std::uint8_t> hit = {1, 1, 1, 0};
  for (int k = 0; k < 4; ++k) {
    pairs.reference.push_back(Colour(100 + k, 50, 20));
    pairs.test.push_back(k == 3 ? Colour::Constant(NAN) : Colour(90 + k, 50, 20));
  }
  const ColourStatistics s = compute_colour_statistics(pairs, hit);
  EXPECT_EQ(s.compared, 3u);
  EXPECT_EQ(s.no_hit, 1u);
  EXPECT_DOUBLE_EQ(s.rgb[0].mean_abs, 10);
  EXPECT_DOUBLE_EQ(s.rgb[0].rms, 10);
  EXPECT_NEAR(s.rgb[0].psnr, 20 * std::log10(25.5), 1e-12);
  EXPECT_TRUE(std::isinf(s.rgb[1].psnr));
  EXPECT_NEAR(s.psnr_rgb, 10 * std::log10(255.0 * 255 / (100.0 / 3)), 1e-12);
  // Y' moves by 0.2126 of R', Cb by Y' / 1.8556, Cr by (R' - Y') / 1.5748.
  EXPECT_NEAR(s.ycbcr[0].rms, 2.126, 1e-12);
  EXPECT_NEAR(s.ycbcr[1].rms, 2.126 / 1.8556, 1e-12);
  EXPECT_NEAR(s.ycbcr[2].rms, 7.874 / 1.5748, 1e-12);
  const double mse_611 = (6 * 2.126 * 2.126 + std::pow(2.126 / 1.8556, 2) + std::pow(7.874 / 1.5748, 2)) / 8;
  EXPECT_NEAR(s.psnr_ycbcr_611, colour_psnr(mse_611), 1e-9);
  EXPECT_GT(s.delta_e_mean, 0);
  EXPECT_GE(s.delta_e_max, s.delta_e_p95);
}

TEST(ColourRule, GradientPlaneMovedByAKnownOffset) {
  // TEST lies 0.5 above REF and its colour field is shifted by 0.5 along x: wherever a sample's
  // line meets it, TEST's R' is REF's less 5 exactly and G', B' agree (the field is linear, so
  // barycentric interpolation reproduces it; float code values near 150 round to 1e-5).
  const TriangleMesh reference = gradient_plane(0, 0);
  const TriangleMesh test = gradient_plane(0.5, 0.5);
  for (const char* method : {"embree", "cgal"}) {
    for (Semantics semantics : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
      for (const char* kind : {"faces", "vertices", "area:2000"}) {
        SCOPED_TRACE(std::string(method) + " " + to_string(semantics) + " " + kind);
        const SampleSet samples = make_samples(reference, parse_sample_spec(kind));
        auto m = make_method(method);
        DistanceOptions options{semantics, 1.0, true};
        const DistanceResult result = measure_distances(*m, test, samples, options);
        ASSERT_EQ(result.hit_face.size(), samples.size());
        const ColourPairs pairs = colour_pairs(reference, samples, test, result, semantics);
        for (std::size_t k = 0; k < samples.size(); ++k) {
          ASSERT_TRUE(result.hit[k]);
          const Colour expected = pairs.reference[k] - Colour(5, 0, 0);
          ASSERT_LT((pairs.test[k] - expected).cwiseAbs().maxCoeff(), 1e-4) << "sample " << k;
        }
        const ColourStatistics s = compute_colour_statistics(pairs, result.hit);
        EXPECT_NEAR(s.rgb[0].mean_abs, 5, 1e-4);
        EXPECT_NEAR(s.rgb[0].psnr, 20 * std::log10(255.0 / 5), 1e-4);
        EXPECT_LT(s.rgb[1].rms, 1e-4);
      }
    }
  }
}

// The baselines' correspondences: v2p-naive's nearest point of a face (the closed form holds
// anywhere), v2v's nearest vertex (straight above each vertex sample here, so it holds there).
TEST(ColourRule, BaselinesGiveTheColourAtTheirCorrespondence) {
  const TriangleMesh reference = gradient_plane(0, 0);
  const TriangleMesh test = gradient_plane(0.5, 0.5);
  const std::pair<const char*, const char*> runs[] = {{"v2p-naive", "faces"}, {"v2p-naive", "area:500"},
                                                      {"v2v-naive", "vertices"}, {"v2v-kdtree", "vertices"}};
  for (const auto& [method, kind] : runs) {
    SCOPED_TRACE(std::string(method) + " " + kind);
    const SampleSet samples = make_samples(reference, parse_sample_spec(kind));
    auto m = make_method(method);
    const DistanceResult result = measure_distances(*m, test, samples, {Semantics::Closest, 1.0, true});
    EXPECT_EQ(result.colour_source, std::string(method).rfind("v2v", 0) == 0 ? "at the nearest vertex" : "on the hit's face");
    const ColourPairs pairs = colour_pairs(reference, samples, test, result, Semantics::Closest);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      ASSERT_LT((pairs.test[k] - (pairs.reference[k] - Colour(5, 0, 0))).cwiseAbs().maxCoeff(), 1e-4) << "sample " << k;
    }
  }
}

TEST(ColourRule, NoHitHasNoColour) {
  // TEST beyond h: every sample a no-hit under first-hit, and none is compared.
  const TriangleMesh reference = gradient_plane(0, 0);
  const TriangleMesh test = gradient_plane(3, 0);
  const SampleSet samples = make_samples(reference, parse_sample_spec("faces"));
  auto m = make_method("embree");
  const DistanceResult result = measure_distances(*m, test, samples, {Semantics::FirstHit, 1.0, true});
  const ColourStatistics s = compute_colour_statistics(
      colour_pairs(reference, samples, test, result, Semantics::FirstHit), result.hit);
  EXPECT_EQ(s.compared, 0u);
  EXPECT_EQ(s.no_hit, samples.size());
}

TEST(ColourRule, EmbreeAndCgalGiveTheSameFacesAndColours) {
  TriangleMesh reference = testing::bunny();
  reference.set_vertex_colours(procedural_colours(reference));
  const double diagonal = reference.bounding_box().diagonal();
  TriangleMesh test = smoothly_perturbed(reference, 0.01 * diagonal, 0.2 * diagonal);
  test.set_vertex_colours(procedural_colours(test));
  // Under the sanitizers 3,000 of each kind's samples, spread over the bunny; the Release suite
  // takes them all.
  for (const char* kind : {"vertices", "faces"}) {
    const SampleSet samples = testing::lighter_under_sanitizers(make_samples(reference, parse_sample_spec(kind)), 3000);
    for (Semantics semantics : {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest}) {
      SCOPED_TRACE(std::string(kind) + " " + to_string(semantics));
      const DistanceOptions options{semantics, 0.05 * diagonal, true};
      auto embree = make_method("embree");
      auto cgal = make_method("cgal");
      const DistanceResult e = measure_distances(*embree, test, samples, options);
      const DistanceResult c = measure_distances(*cgal, test, samples, options);
      const ColourPairs pe = colour_pairs(reference, samples, test, e, semantics);
      const ColourPairs pc = colour_pairs(reference, samples, test, c, semantics);
      std::size_t other_faces = 0;
      for (std::size_t k = 0; k < samples.size(); ++k) {
        ASSERT_EQ(e.hit[k], c.hit[k]);
        if (!e.hit[k]) continue;
        // The shared rule decides faces too (ties to the lowest): identical along the normal.
        // Closest: equally near faces may differ (CGAL keeps its first); they meet at the
        // closest point, where the colour is the same up to the interpolation's rounding.
        if (semantics != Semantics::Closest) {
          ASSERT_EQ(e.hit_face[k], c.hit_face[k]) << "sample " << k;
          // The tie goes to the lower face with its value, so even a zero's sign agrees.
          ASSERT_EQ(std::signbit(e.signed_distance[k]), std::signbit(c.signed_distance[k])) << "sample " << k;
          ASSERT_EQ(pe.test[k], pc.test[k]) << "sample " << k;
        } else {
          other_faces += e.hit_face[k] != c.hit_face[k];
          ASSERT_LT((pe.test[k] - pc.test[k]).cwiseAbs().maxCoeff(), 1e-3) << "sample " << k;
        }
      }
      if (semantics == Semantics::Closest)
        RecordProperty("closest_other_faces", static_cast<int>(other_faces));
    }
  }
}

}  // namespace
}  // namespace roving
