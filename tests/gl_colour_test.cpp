// Colour by the frame buffer (the paper's Section 1): each GL method's colour against the exact
// answer on the same samples, on planes whose colour is known in closed form, a checkerboard's
// texel centres, and coloured and textured bunnies against recoloured, moved copies.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "analytic.h"
#include "colour_models.h"
#include "coloured.h"
#include "roving/core/colour.h"
#include "roving/core/colour_statistics.h"
#include "roving/core/error.h"
#include "roving/core/normalise.h"
#include "roving/formats/meshes/mesh_io.h"
#include "roving/gl_methods/gl_methods.h"
#include "roving/gl_methods/image_based.h"
#include "roving/registry/method_registry.h"
#include "test_support.h"

namespace roving {
namespace {

const char* const kGlMethods[] = {"roving", "viewpoint", "cooperative"};

class EachBackend : public ::testing::TestWithParam<GlBackend> {
 protected:
  DistanceResult measure(const char* method, const TriangleMesh& test, const SampleSet& samples,
                         double h) const {
    GlMethodOptions gl;
    gl.backend = GetParam();
    auto m = make_method(method, gl);
    return measure_distances(*m, test, samples, {Semantics::FirstHit, h, true});
  }
};

// Vertex colours are interpolated in float by the rasteriser, in a tile's frame where a triangle
// spans up to 1e6 tile half-widths: a few float ulps of the field's range over a triangle (10
// code values here), far below a thousandth of a step.
constexpr double kVertexColourTolerance = 1e-3;

TEST_P(EachBackend, GradientPlaneMovedByAKnownOffset) {
  REQUIRE_GL_CONTEXT(GetParam());
  // TEST 0.5 above REF, its linear colour field moved 0.5 along x: TEST's R' is REF's less 5 at
  // every point the normal meets, G' and B' the same. A view's d errs a little along the normal,
  // where the field does not change.
  const TriangleMesh reference = testing::gradient_plane(0, 0);
  const TriangleMesh test = testing::gradient_plane(0.5, 0.5);
  const SampleSet samples = make_samples(reference, parse_sample_spec("faces"));
  const std::vector<Colour> expected = sample_colours(reference, samples);
  for (const char* method : kGlMethods) {
    SCOPED_TRACE(method);
    const DistanceResult r = measure(method, test, samples, 1.0);
    ASSERT_EQ(r.hit_colour.size(), samples.size());
    std::size_t hits = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (!r.hit[k]) continue;
      ++hits;
      ASSERT_LT((r.hit_colour[k] - (expected[k] - Colour(5, 0, 0))).cwiseAbs().maxCoeff(),
                kVertexColourTolerance)
          << "sample " << k << ": " << r.hit_colour[k].transpose();
    }
    EXPECT_GT(hits, samples.size() / 2);
  }
}

TEST_P(EachBackend, RecolouredRampTextureOnAMovedPlane) {
  REQUIRE_GL_CONTEXT(GetParam());
  // A ramp texture (R up 5 a column, G down 4 a row) across the square from texel centre to
  // centre, so its bilinear colour is linear; TEST 0.5 above with R less 5. The texels go to GL as
  // float (exact), and GPUs filter with weights of 8 fractional bits: the drawn colour is within
  // a 256th of the largest step between texels (5) of the exact one, and float's rounding.
  const int n = 32;
  const auto ramp = [](int shift) {
    return [shift](int i, int j) { return Eigen::Vector3i(40 + 5 * i - shift, 200 - 4 * j, 90); };
  };
  const TriangleMesh reference =
      testing::textured_square(0, std::make_shared<Texture>(testing::make_texture(n, n, ramp(0))));
  const TriangleMesh test =
      testing::textured_square(0.5, std::make_shared<Texture>(testing::make_texture(n, n, ramp(5))));
  const SampleSet samples = make_samples(reference, parse_sample_spec("area:2000"));
  auto embree = make_method("embree");
  const DistanceResult exact = measure_distances(*embree, test, samples, {Semantics::FirstHit, 1.0, true});
  const ColourPairs truth = colour_pairs(reference, samples, test, exact, Semantics::FirstHit);
  const double tolerance = 5.0 / 256 + kVertexColourTolerance;
  for (const char* method : kGlMethods) {
    SCOPED_TRACE(method);
    const DistanceResult r = measure(method, test, samples, 1.0);
    std::size_t hits = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (!r.hit[k]) continue;
      ++hits;
      ASSERT_LT((r.hit_colour[k] - truth.test[k]).cwiseAbs().maxCoeff(), tolerance)
          << "sample " << k << ": " << r.hit_colour[k].transpose() << " against "
          << truth.test[k].transpose();
      ASSERT_LT((truth.test[k] - (truth.reference[k] - Colour(5, 0, 0))).cwiseAbs().maxCoeff(), 1e-4);
    }
    EXPECT_GT(hits, samples.size() / 2);
  }
}

TEST_P(EachBackend, CheckerboardTexelCentresUnderEitherFilter) {
  REQUIRE_GL_CONTEXT(GetParam());
  // Samples straight under a checkerboard's texel centres: under either filter the colour there is
  // the texel's, with no neighbour's weight, so GL draws it exactly.
  const int n = 8;
  for (const Filter filter : {Filter::Linear, Filter::Nearest}) {
    Sampler sampler;
    sampler.filter = filter;
    const auto board = std::make_shared<Texture>(testing::checkerboard(n));
    const TriangleMesh test = testing::textured_square(0.5, board, sampler);
    // The square maps texel centre to texel centre: texel (i, j)'s centre is at x = 10 i / (n - 1),
    // y = 10 (n - 1 - j) / (n - 1); stay off the square's rim, where a view cannot read.
    SampleSet samples;
    samples.kind = "area:texel centres";
    for (int j = 1; j + 1 < n; ++j) {
      for (int i = 1; i + 1 < n; ++i) {
        samples.positions.emplace_back(10.0 * i / (n - 1), 10.0 * (n - 1 - j) / (n - 1), 0);
        samples.normals.emplace_back(0, 0, 1);
        samples.weights.push_back(1);
        samples.elements.push_back(0);
      }
    }
    for (const char* method : kGlMethods) {
      SCOPED_TRACE(std::string(method) + (filter == Filter::Linear ? " linear" : " nearest"));
      const DistanceResult r = measure(method, test, samples, 1.0);
      std::size_t k = 0, hits = 0;
      for (int j = 1; j + 1 < n; ++j) {
        for (int i = 1; i + 1 < n; ++i, ++k) {
          if (!r.hit[k]) continue;
          ++hits;
          ASSERT_LT((r.hit_colour[k] - board->texel(i, j)).cwiseAbs().maxCoeff(), kVertexColourTolerance)
              << "texel " << i << ", " << j << ": " << r.hit_colour[k].transpose();
        }
      }
      if (std::string(method) != "viewpoint") {
        EXPECT_EQ(hits, samples.size());
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, EachBackend, ::testing::Values(GlBackend::OSMesa, GlBackend::Egl),
                         [](const ::testing::TestParamInfo<GlBackend>& info) {
                           return std::string(to_string(info.param));
                         });

// How a GL method's colours compare with Embree's on the samples both hit: the share within one
// 8-bit step in every channel, and the colour PSNRs of each over those samples.
struct ColourAgreement {
  std::size_t both = 0, within_a_step = 0;
  ColourStatistics exact, drawn;
  double within_fraction() const { return double(within_a_step) / double(both); }
};

ColourAgreement colour_agreement(const ColourPairs& exact, const ColourPairs& drawn, const DistanceResult& e,
                                 const DistanceResult& d) {
  ColourAgreement a;
  std::vector<std::uint8_t> both(e.hit.size(), 0);
  for (std::size_t k = 0; k < both.size(); ++k) {
    if (!e.hit[k] || !d.hit[k]) continue;
    both[k] = 1;
    ++a.both;
    a.within_a_step += (exact.test[k] - drawn.test[k]).cwiseAbs().maxCoeff() <= 1;
  }
  a.exact = compute_colour_statistics(exact, both);
  a.drawn = compute_colour_statistics(drawn, both);
  return a;
}

// The bunny (normalised) against a copy moved smoothly by up to 0.5% of the diagonal and
// recoloured: vertex colours of the procedural field, or a procedural texture (with stripes)
// projected along z. Every GL method's colour is within one step of Embree's on >= 99.9% of the
// samples both hit, and its PSNRs within 0.1 dB.
TEST(BunnyColour, GlMethodsAgreeWithEmbree) {
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const TriangleMesh bunny = normalised(testing::bunny());
  const double diagonal = bunny.bounding_box().diagonal();
  const TriangleMesh moved = smoothly_perturbed(bunny, 0.005 * diagonal, 0.3 * diagonal);
  TriangleMesh coloured_reference = bunny, coloured_test = moved;
  coloured_reference.set_vertex_colours(procedural_colours(bunny));
  std::vector<Colour> recoloured = procedural_colours(moved, bunny.bounding_box());
  for (Colour& c : recoloured) c.x() = std::min(255.0f, c.x() * 1.05f);
  coloured_test.set_vertex_colours(recoloured);
  const TriangleMesh textured_reference =
      with_planar_texture(bunny, std::make_shared<Texture>(procedural_texture(512, 0, 40)));
  const TriangleMesh textured_test = with_planar_texture(
      moved, std::make_shared<Texture>(procedural_texture(512, 0.2, 40)), {}, bunny.bounding_box());
  const std::pair<const TriangleMesh*, const TriangleMesh*> pairs[] = {{&coloured_reference, &coloured_test},
                                                                       {&textured_reference, &textured_test}};
  const double h = 0.05 * diagonal;
  for (const auto& [reference, test] : pairs) {
    const SampleSet samples = make_samples(*reference, {});
    auto embree = make_method("embree");
    const DistanceResult e = measure_distances(*embree, *test, samples, {Semantics::FirstHit, h, true});
    const std::vector<Colour> reference_colours = sample_colours(*reference, samples);
    const ColourPairs exact = colour_pairs(reference_colours, samples, *test, e, Semantics::FirstHit);
    for (const char* method : kGlMethods) {
      SCOPED_TRACE(std::string(method) + (reference->texture_mapping() ? " textured" : " vertex colours"));
      auto m = make_method(method);
      const DistanceResult d = measure_distances(*m, *test, samples, {Semantics::FirstHit, h, true});
      const ColourAgreement a = colour_agreement(
          exact, colour_pairs(reference_colours, samples, *test, d, Semantics::FirstHit), e, d);
      EXPECT_GE(a.within_fraction(), 0.999) << a.within_a_step << " of " << a.both;
      EXPECT_NEAR(a.drawn.psnr_rgb, a.exact.psnr_rgb, 0.1);
      EXPECT_NEAR(a.drawn.psnr_ycbcr_611, a.exact.psnr_ycbcr_611, 0.1);
      EXPECT_GT(a.both, samples.size() / 2);
      RecordProperty(
          std::string(method) + (reference->texture_mapping() ? "_textured" : "_vertex") + "_within",
          std::to_string(a.within_fraction()));
    }
  }
}

// The bunny (normalised) along its normals by `offset`, vertex by vertex: each vertex sample's
// normal line then passes through TEST's vertex, where the faces around it meet.
TriangleMesh moved_along_vertex_normals(const TriangleMesh& mesh, double offset) {
  std::vector<Vec3> positions = mesh.positions().to_vector();
  const std::vector<Vec3> normals = mesh.vertex_normals();
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (normals[v].norm() > 0) positions[v] += offset * normals[v].normalized();
  }
  return TriangleMesh(std::move(positions), mesh.triangles());
}

// Where faces meet with different colours (seams), TEST's colour is the lowest-numbered face's
// among those that give the chosen d (colour.md), and the GL methods make the same choice as
// Embree: a colour per face, by a one-texel-per-face atlas (every vertex a seam) or by
// face-varying vertex colours on a triangle soup (a glTF's split seam vertices), on TEST the
// same as REF and moved along the vertex normals (vertex samples meet TEST's vertices), for
// vertex, face and area samples, with exact roving's cameras built on the CPU and on the GPU.
TEST(SeamColour, GlMethodsTakeTheFaceTheRuleTakes) {
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const TriangleMesh bunny = normalised(testing::bunny());
  const double diagonal = bunny.bounding_box().diagonal();
  const TriangleMesh moved = moved_along_vertex_normals(bunny, 0.002 * diagonal);
  struct Case {
    const char* name;
    TriangleMesh test;
    bool moved;
  };
  std::vector<Case> tests;
  tests.push_back({"atlas, moved", testing::with_a_texel_per_face(moved), true});
  tests.push_back({"soup, same", testing::soup_coloured_per_face(bunny), false});
  tests.push_back({"atlas, same", testing::with_a_texel_per_face(bunny), false});
  tests.push_back({"soup, moved", testing::soup_coloured_per_face(moved), true});
  SampleSpec area;
  area.kind = SampleSpec::Kind::Area;
  area.count = 20000;
  SampleSpec vertices;
  vertices.kind = SampleSpec::Kind::Vertices;
  // Under the sanitizers one setting drives every code path: the agreement itself is checked over
  // all four by the Release suite.
  std::vector<std::pair<SampleSpec, double>> runs = {{vertices, 0.02}};
  if (!testing::kUnderSanitizers) runs.insert(runs.end(), {{vertices, 0.05}, {SampleSpec{}, 0.05}, {area, 0.02}});
  for (const auto& [spec, h_fraction] : runs) {
    // Under the sanitizers 3,000 of them, spread over the bunny.
    const SampleSet samples = testing::lighter_under_sanitizers(make_samples(bunny, spec), 3000);
    const std::vector<Colour> reference_colours(samples.size(), Colour::Constant(128));
    const double h = h_fraction * diagonal;
    for (const Case& c : tests) {
      auto embree = make_method("embree");
      const DistanceResult e = measure_distances(*embree, c.test, samples, {Semantics::FirstHit, h, true});
      const ColourPairs exact = colour_pairs(reference_colours, samples, c.test, e, Semantics::FirstHit);
      // Every GL method, and exact roving with its cameras built on the GPU or computed.
      for (const auto& [method, geometry] :
           {std::pair("roving", CameraGeometry::Cpu), {"roving", CameraGeometry::Gpu},
            {"roving", CameraGeometry::Compute}, {"viewpoint", CameraGeometry::Cpu},
            {"cooperative", CameraGeometry::Cpu}}) {
        const std::string name = std::string(method) + " (cameras " + to_string(geometry) + "), " + c.name +
                                 ", " + spec.to_string() + ", h " + std::to_string(h_fraction);
        SCOPED_TRACE(name);
        GlMethodOptions gl;
        gl.camera_geometry = geometry;
        auto m = make_method(method, gl);
        const DistanceResult d = measure_distances(*m, c.test, samples, {Semantics::FirstHit, h, true});
        const ColourAgreement a = colour_agreement(
            exact, colour_pairs(reference_colours, samples, c.test, d, Semantics::FirstHit), e, d);
        // Viewpoint sampling alone leaves d within 100 view depth steps of 0 to roving
        // (viewpoint_sampling.cpp): on TEST = REF it resolves next to nothing.
        if (std::string(method) == "viewpoint" && !c.moved) continue;
        EXPECT_GE(a.within_fraction(), 0.999) << a.within_a_step << " of " << a.both;
        EXPECT_NEAR(a.drawn.psnr_rgb, a.exact.psnr_rgb, 0.01);
        EXPECT_GT(a.both, samples.size() / 2);
        EXPECT_EQ(d.gl->camera_geometry, geometry);
        RecordProperty(name, std::to_string(a.within_a_step) + " of " + std::to_string(a.both));
      }
    }
  }
}

}  // namespace
}  // namespace roving

namespace roving {
namespace {

// The image-based comparison (MPEG's IBSM) on closed forms: identical models agree exactly
// (mmetric's 99.99 dB); a colour moved by 5 in R' on every pixel gives R's PSNR of
// 20 log10(255 / 5) and the others 99.99; a TEST covering half of REF's square leaves as many pixels
// unmatched as matched.
TEST(ImageBased, ClosedForms) {
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const auto square = [](double width, float red) {
    TriangleMesh mesh({Vec3(0, 0, 0), Vec3(width, 0, 0), Vec3(width, 10, 0), Vec3(0, 10, 0)},
                      {{0, 1, 2}, {0, 2, 3}});
    mesh.set_vertex_colours(std::vector<Colour>(4, Colour(red, 100, 50)));
    return mesh;
  };
  ImageBasedOptions options;
  options.resolution = 512;
  const ImageBasedResult same = image_based_comparison(square(10, 100), square(10, 100), options);
  EXPECT_GT(same.matched_pixels, 0u);
  EXPECT_EQ(same.unmatched_pixels, 0u);
  EXPECT_EQ(same.psnr_rgb, 99.99);
  EXPECT_EQ(same.psnr_ycbcr_611, 99.99);
  EXPECT_EQ(same.depth_psnr, 99.99);
  const ImageBasedResult red = image_based_comparison(square(10, 100), square(10, 105), options);
  EXPECT_EQ(red.matched_pixels, same.matched_pixels);
  EXPECT_DOUBLE_EQ(red.rgb_mse[0], 25);
  EXPECT_DOUBLE_EQ(red.rgb_mse[1], 0);
  EXPECT_NEAR(red.psnr_rgb, 10 * std::log10(255.0 * 255 / (25.0 / 3)), 1e-9);
  EXPECT_NEAR(red.psnr_rgb_channels[0], 20 * std::log10(255.0 / 5), 1e-9);
  EXPECT_EQ(red.psnr_rgb_channels[1], 99.99);
  EXPECT_NEAR(red.ycbcr_mse[0], std::pow(0.2126 * 5, 2), 1e-9);
  // Half the square: the matched pixels are TEST's, the unmatched REF's other half, as many. Pixel
  // edges (1/512 of the view, 0.028 units) along a 25-unit boundary err by under 2% of 50 units^2.
  const ImageBasedResult half = image_based_comparison(square(10, 100), square(5, 100), options);
  EXPECT_NEAR(half.unmatched_percent, 100, 2);
  EXPECT_NEAR(double(half.matched_pixels), 0.5 * double(same.matched_pixels),
              0.02 * double(same.matched_pixels));
  // mmetric's directions: 16 on the unit sphere from +y to -y.
  const std::vector<Vec3> directions = fibonacci_directions(16);
  EXPECT_EQ(directions.size(), 16u);
  EXPECT_NEAR((directions.front() - Vec3::UnitY()).norm(), 0, 1e-12);
  EXPECT_NEAR((directions.back() + Vec3::UnitY()).norm(), 0, 1e-12);
  for (const Vec3& d : directions) EXPECT_NEAR(d.norm(), 1, 1e-12);
  options.views = 1;
  EXPECT_THROW(image_based_comparison(square(10, 100), square(10, 100), options), Error);
}

// mmetric's own figures (v1.1.7, tests/ibsm/README.md: how it was built and run) on our pairs:
// vertex colours on a closed and an open model, textures whose UVs reach 0 and 1, a coarser model
// under the same texture, and models of different size. Every figure it prints agrees within
// 0.01 dB (0.01 points for the percentages): float depths and edge pixels are where the two
// rasterisers may differ.
std::map<std::string, double> mmetric_figures(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  std::map<std::string, double> figures;
  const std::string output = text.str();
  const std::regex line(R"(^(\w+)\s+PSNR = ([0-9.]+)$|^(UnmatchedPixelPercentage|BoxRatio) = ([0-9.e+-]+)$)",
                        std::regex::multiline);
  for (auto it = std::sregex_iterator(output.begin(), output.end(), line); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    figures[m[1].matched ? m[1].str() : m[3].str()] = std::stod(m[1].matched ? m[2].str() : m[4].str());
  }
  return figures;
}

TEST(ImageBased, MmetricsOwnFiguresOnOurPairs) {
  REQUIRE_GL_CONTEXT(default_gl_backend());
  const std::string folder = std::string(ROVING_SOURCE_DIR) + "/tests/ibsm/";
  for (const auto& [name, a, b] : {std::tuple{"sphere", "sphere-a.ply", "sphere-b.ply"},
                                   {"cap", "cap-a.ply", "cap-b.ply"},
                                   {"torus", "torus-a.obj", "torus-b.obj"},
                                   {"globe", "globe-a.obj", "globe-b.obj"}}) {
    SCOPED_TRACE(name);
    const std::map<std::string, double> mmetric = mmetric_figures(folder + "mmetric-1.1.7/" + name + ".txt");
    ASSERT_EQ(mmetric.size(), 11u);
    const ImageBasedResult ours =
        image_based_comparison(load_mesh(folder + a).mesh, load_mesh(folder + b).mesh, ImageBasedOptions{});
    ASSERT_TRUE(ours.colour);
    const std::map<std::string, double> figures = {
        {"R", ours.psnr_rgb_channels[0]}, {"G", ours.psnr_rgb_channels[1]},
        {"B", ours.psnr_rgb_channels[2]}, {"RGB", ours.psnr_rgb},
        {"Y", ours.psnr_ycbcr[0]},        {"U", ours.psnr_ycbcr[1]},
        {"V", ours.psnr_ycbcr[2]},        {"YUV", ours.psnr_ycbcr_611},
        {"GEO", ours.depth_psnr},         {"UnmatchedPixelPercentage", ours.unmatched_percent},
        {"BoxRatio", ours.box_ratio}};
    for (const auto& [figure, value] : figures) {
      EXPECT_NEAR(value, mmetric.at(figure), 0.01) << figure;
    }
  }
}

}  // namespace
}  // namespace roving
