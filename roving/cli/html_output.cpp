// The measurement page's contents, from the report.
#include "html_output.h"

#include <fmt/format.h>

#include <filesystem>

#include "measure.h"
#include "roving/core/colour_statistics.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/html/display_surface.h"
#include "roving/html/distance_view.h"
#include "roving/measurement/figure_families.h"

namespace roving {
namespace {

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// Delta E and both models' colours per displayed element, decimated as d is (display_surface).
HtmlView::Colours colour_layers(const TriangleMesh* surface, const HeatmapLayout& layout,
                                const DirectionReport& d) {
  HtmlView::Colours c;
  const std::vector<float> delta_e = sample_delta_e(*d.colour_pairs, d.result.hit);
  c.delta_e = display_surface(surface, layout, d.samples, delta_e, kHtmlMaxTriangles).values;
  c.delta_e_range = percentile_99(delta_e, 1);
  for (const auto& [colours, out] :
       {std::pair(&d.colour_pairs->reference, &c.reference), {&d.colour_pairs->test, &c.test}}) {
    std::vector<std::vector<float>> channels(3);
    for (int k = 0; k < 3; ++k) {
      std::vector<float> channel(colours->size());
      for (std::size_t i = 0; i < channel.size(); ++i)
        channel[i] = (*colours)[i][k];  // TEST's: NaN at a no-hit
      channels[k] = display_surface(surface, layout, d.samples, channel, kHtmlMaxTriangles).values;
    }
    out->resize(3 * channels[0].size());
    for (std::size_t e = 0; e < channels[0].size(); ++e)
      for (int k = 0; k < 3; ++k) (*out)[3 * e + k] = channels[k][e];
  }
  return c;
}

HtmlView direction_view(const DirectionReport& d, const MeasureReport& report) {
  const Model& reference = *d.reference;
  const TriangleMesh* surface = reference.type == ModelType::Points ? nullptr : &reference.mesh.mesh;
  HtmlView view = distance_view(surface, heatmap_layout(reference, d.samples), d.samples, d.result,
                                d.statistics, d.heatmap_range, report.diagonal, report.max_error);
  view.label = d.label;
  view.title = fmt::format("{} (REF) against {} (TEST){}", file_name(reference.path()),
                           file_name(d.test->path()), d.label.empty() ? "" : ", " + d.label);
  view.subtitle =
      fmt::format("d by {}, {} semantics, {} samples ({}), h = {:.4g}", report.method,
                  to_string(report.semantics), d.samples.size(), d.samples.kind, report.max_error);
  view.method = report.method;
  // Before the last two rows (query time, colour range): the intervals where there are some, and
  // the colour figures where both models have colour.
  const auto at = view.figures.end() - 2;
  std::vector<std::pair<std::string, std::string>> intervals;
  if (d.intervals) {
    intervals.push_back({"USiAD, 95% interval", fmt::format("[{:.6g}, {:.6g}]", d.intervals->usiad.lower,
                                                            d.intervals->usiad.upper)});
  }
  if (d.hausdorff) {
    intervals.push_back(
        {"Hausdorff, certified", fmt::format("[{:.6g}, {:.6g}]", d.hausdorff->lower, d.hausdorff->upper)});
  }
  if (d.colour) {
    const ColourStatistics& c = *d.colour;
    intervals.push_back({"colour: PSNR Y'CbCr 6:1:1", fmt::format("{:.2f} dB", c.psnr_ycbcr_611)});
    intervals.push_back({"colour: PSNR R'G'B'", fmt::format("{:.2f} dB", c.psnr_rgb)});
    intervals.push_back(
        {"colour: delta E mean / p95 / max",
         fmt::format("{:.3g} / {:.3g} / {:.3g}", c.delta_e_mean, c.delta_e_p95, c.delta_e_max)});
  }
  view.figures.insert(at, intervals.begin(), intervals.end());
  if (d.colour_pairs) view.colours = colour_layers(surface, heatmap_layout(reference, d.samples), d);
  return view;
}

// Metro's two-sided summary over both directions' samples.
HtmlFigures two_sided_figures(const MeasureReport& report) {
  const TwoSided t = report.two_sided();
  const auto length = [&](double x) { return fmt::format("{:.6g} ({:.4g}%)", x, 100 * x / report.diagonal); };
  // Only the closest point makes the largest |d| the Hausdorff distance: along a normal line, a
  // first hit on another part of TEST (a false alarm) can be far larger.
  const char* largest =
      report.semantics == Semantics::Closest ? "Hausdorff (max |d| of both)" : "max |d| of both (not a Hausdorff distance)";
  HtmlFigures figures{"Both directions", {{largest, length(t.max_abs)}}};
  if (t.certified) {
    figures.rows.push_back(
        {"Hausdorff, certified", fmt::format("[{:.6g}, {:.6g}]", t.hausdorff_lower, t.hausdorff_upper)});
  }
  figures.rows.push_back({"mean |d| of both", length(t.mean_abs)});
  figures.rows.push_back({"RMS of both", length(t.rms)});
  return figures;
}

}  // namespace

HtmlPage measurement_page(const MeasureReport& report, const std::string& text, const nlohmann::json& json,
                          HeatmapQuantity shown) {
  HtmlPage page;
  page.shown_first = shown == HeatmapQuantity::DeltaE ? "delta_e" : "d";
  const DirectionReport& first = report.directions.front();
  page.title = fmt::format("{} {} {}: surface roving report", file_name(first.reference->path()),
                           report.symmetric() ? "and" : "against", file_name(first.test->path()));
  for (const DirectionReport& d : report.directions) page.views.push_back(direction_view(d, report));
  if (report.symmetric()) page.pair_figures.push_back(two_sided_figures(report));
  for (const FigureFamily& family : figure_families()) {
    if (json.contains(family.section)) page.pair_figures.push_back({family.title, family.page_figures(json)});
  }
  page.warnings = report.warnings;
  page.report_text = text;
  page.report = json;
  return page;
}

}  // namespace roving
