// The web page's parts that need no browser (tests/browser/ checks the page in Chromium): the
// display surface and its decimation, and what the page writer embeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "roving/core/sample_set.h"
#include "roving/html/display_surface.h"
#include "roving/html/html_page.h"
#include "test_support.h"

namespace roving {
namespace {

// The square [-1, 1]^2 at z = 0 in n x n cells, two triangles each.
TriangleMesh square(int n) {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) positions.emplace_back(-1 + 2.0 * i / n, -1 + 2.0 * j / n, 0);
  }
  const auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return TriangleMesh(positions, triangles);
}

// Per face sample: d = 1 where the face lies at x < 0, no hit (NaN) at x > 0.
std::vector<float> half_and_half(const TriangleMesh& mesh, const SampleSet& samples) {
  std::vector<float> d;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    d.push_back(mesh.centroid(samples.elements[k]).x() < 0 ? 1.0f : std::numeric_limits<float>::quiet_NaN());
  }
  return d;
}

TEST(DisplaySurface, UnderTheBudgetIsTheSurfaceItself) {
  const TriangleMesh mesh = square(20);
  const SampleSet samples = make_samples(mesh, parse_sample_spec("faces"));
  const DisplaySurface s = display_surface(&mesh, {HeatmapElement::Faces, 1}, samples, half_and_half(mesh, samples), 800);
  EXPECT_FALSE(s.decimated());
  ASSERT_EQ(s.triangles.size(), 3 * mesh.triangle_count());
  EXPECT_EQ(s.positions.size(), 3 * mesh.vertex_count());
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    EXPECT_EQ(s.samples[f], static_cast<std::int32_t>(f));
    EXPECT_EQ(std::isnan(s.values[f]), mesh.centroid(f).x() > 0);
  }
}

TEST(DisplaySurface, OverTheBudgetMergesVerticesAndKeepsEachRegionsValue) {
  const TriangleMesh mesh = square(200);  // 80,000 triangles
  const SampleSet samples = make_samples(mesh, parse_sample_spec("faces"));
  const std::size_t budget = 5000;
  const DisplaySurface s = display_surface(&mesh, {HeatmapElement::Faces, 1}, samples, half_and_half(mesh, samples), budget);
  ASSERT_TRUE(s.decimated());
  const std::size_t triangles = s.triangles.size() / 3;
  EXPECT_LE(triangles, budget);
  EXPECT_GT(triangles, budget / 4) << "the grid was coarsened far more than the budget asks";
  ASSERT_EQ(s.values.size(), triangles);
  double covered = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    EXPECT_EQ(s.samples[t], kMerged);
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.triangles[3 * t + k];
      ASSERT_LT(3 * v + 2, s.positions.size());
      p[k] = Vec3(s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2]);
    }
    covered += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const double x = (p[0].x() + p[1].x() + p[2].x()) / 3;
    // Away from x = 0 a merged triangle merges faces of one kind: their value, exactly.
    if (x < -0.1) {
      EXPECT_EQ(s.values[t], 1.0f) << "at x = " << x;
    } else if (x > 0.1) {
      EXPECT_TRUE(std::isnan(s.values[t])) << "at x = " << x;
    }
  }
  // The merged surface still covers the square, less the border cells' shrinkage.
  EXPECT_GT(covered, 0.9 * 4);
  EXPECT_LT(covered, 4 + 1e-3);
}

TEST(DisplaySurface, PointsAreSubsampledEvenlyToTheBudget) {
  const TriangleMesh mesh = square(100);
  const SampleSet samples = make_samples(mesh, parse_sample_spec("area:10000"));
  const std::vector<float> d(samples.size(), 0.5f);
  const DisplaySurface s = display_surface(nullptr, {HeatmapElement::Points, 1}, samples, d, 3000);
  EXPECT_LE(s.values.size(), 3000u);
  EXPECT_GE(s.values.size(), 2500u);
  EXPECT_TRUE(s.triangles.empty());
  EXPECT_EQ(s.source_elements, samples.size());
  // Disks of the area each shown point stands for (the square's 4 over 2,500 to 3,000 points).
  const double radius = 1.25 * std::sqrt(4.0 / s.values.size() / M_PI);
  EXPECT_NEAR(s.point_size, 2 * radius, 1e-6);
  for (std::size_t i = 1; i < s.samples.size(); ++i) EXPECT_EQ(s.samples[i] - s.samples[i - 1], s.samples[1] - s.samples[0]);
}

std::string page_text(const HtmlPage& page) {
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file(std::tmpfile(), &std::fclose);
  write_html_page(file.get(), page);
  std::string text(static_cast<std::size_t>(std::ftell(file.get())), '\0');
  std::rewind(file.get());
  EXPECT_EQ(std::fread(text.data(), 1, text.size(), file.get()), text.size());
  return text;
}

TEST(HtmlPage, EmbedsItsScriptsAndEscapesWhatTheInputsSay) {
  const TriangleMesh mesh = square(4);
  const SampleSet samples = make_samples(mesh, parse_sample_spec("faces"));
  HtmlPage page;
  page.title = "a.obj <b> & c.obj";
  HtmlView view;
  view.surface = display_surface(&mesh, {HeatmapElement::Faces, 1}, samples, half_and_half(mesh, samples), 100);
  view.range = 1;
  view.diagonal = std::sqrt(8.0);
  page.views.push_back(view);
  page.warnings = {"</script><script>alert(1)</script>"};  // a file name can say anything
  page.report_text = "x < y";
  page.report = {{"note", "</script>"}};
  const std::string text = page_text(page);
  EXPECT_EQ(text.find("<script>alert"), std::string::npos);
  EXPECT_NE(text.find("&lt;/script&gt;&lt;script&gt;alert(1)"), std::string::npos);
  EXPECT_NE(text.find("<title>a.obj &lt;b&gt; &amp; c.obj</title>"), std::string::npos);
  EXPECT_NE(text.find("<pre>x &lt; y</pre>"), std::string::npos);
  EXPECT_NE(text.find(R"({"note":"<\/script>"})"), std::string::npos);
  // Every script inline: three.js, OrbitControls and the viewer; nothing loaded from elsewhere.
  EXPECT_NE(text.find("THREE.OrbitControls"), std::string::npos);
  EXPECT_NE(text.find("REVISION=\"111\""), std::string::npos);
  EXPECT_EQ(text.find("<script src"), std::string::npos);
  EXPECT_EQ(text.find("<link"), std::string::npos);
}

// The report's provenance (top-level tool, command line, inputs) as a table, escaped; an input not
// hashed (a stream) shows null rather than failing.
TEST(HtmlPage, ShowsTheReportsProvenance) {
  HtmlPage page;
  page.report = {{"tool", {{"name", "roving"}, {"version", "1.2.3"}, {"commit", "abc"}}},
                 {"command_line", "roving measure a.obj 'b <c>.obj'"},
                 {"inputs",
                  {{{"role", "reference"}, {"path", "a.obj"}, {"bytes", 12}, {"sha256", "0f1e"}},
                   {{"role", "test"}, {"path", "b <c>.obj"}, {"bytes", nullptr}, {"sha256", nullptr}}}}};
  const std::string text = page_text(page);
  EXPECT_NE(text.find("<summary>Provenance</summary>"), std::string::npos);
  EXPECT_NE(text.find("<td>roving 1.2.3 (commit abc)</td>"), std::string::npos);
  EXPECT_NE(text.find("<td>roving measure a.obj &#39;b &lt;c&gt;.obj&#39;</td>"), std::string::npos);
  EXPECT_NE(text.find("<th>reference</th><td>a.obj (12 bytes, sha256 0f1e)</td>"), std::string::npos);
  EXPECT_NE(text.find("<th>test</th><td>b &lt;c&gt;.obj (null bytes, sha256 null)</td>"), std::string::npos);
  // No provenance in the report: no empty section.
  EXPECT_EQ(page_text(HtmlPage{}).find("Provenance"), std::string::npos);
}

}  // namespace
}  // namespace roving
