// The measurement page's contents, from the report.
#include "html_output.h"

#include <fmt/format.h>

#include <filesystem>

#include "measure.h"
#include "roving/formats/heatmap.h"

namespace roving {
namespace {

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// The hits' signed d over twice the colour range (the statistics' own histogram spans [-h, h],
// where h is often far wider than the data).
Histogram display_histogram(const DistanceResult& result, double range) {
  Histogram h;
  h.low = -2 * range, h.high = 2 * range;
  h.counts.assign(64, 0);
  for (std::size_t k = 0; k < result.hit.size(); ++k) {
    if (!result.hit[k]) continue;
    const double position = (result.signed_distance[k] - h.low) / (h.high - h.low) * h.counts.size();
    if (position < 0) {
      ++h.below;
    } else if (position >= h.counts.size()) {
      ++h.above;
    } else {
      ++h.counts[static_cast<std::size_t>(position)];
    }
  }
  return h;
}

HtmlView direction_view(const DirectionReport& d, const MeasureReport& report) {
  const Model& reference = *d.reference;
  HtmlView view;
  view.label = d.label;
  view.title = fmt::format("{} (REF) against {} (TEST){}", file_name(reference.path()), file_name(d.test->path()),
                           d.label.empty() ? "" : ", " + d.label);
  view.subtitle = fmt::format("d by {}, {} semantics, {} samples ({}), h = {:.4g}", report.method,
                              to_string(report.semantics), d.samples.size(), d.samples.kind, report.max_error);
  const TriangleMesh* surface = reference.type == ModelType::Points ? nullptr : &reference.mesh.mesh;
  view.surface = display_surface(surface, heatmap_layout(reference, d.samples), d.samples, distances_or_nan(d.result),
                                 kHtmlMaxTriangles);
  if (d.result.gl) {
    for (Resolution r : d.result.gl->resolved_by) view.resolution.push_back(static_cast<std::uint8_t>(r));
  }
  view.method = report.method;
  view.range = d.heatmap_range;
  view.diagonal = report.diagonal;
  view.max_error = report.max_error;
  const SignCounts signs = sign_counts(d.result);
  view.positive = signs.positive, view.negative = signs.negative, view.zero = signs.zero;
  view.no_hit = d.statistics.no_hit_count;
  if (view.range > 0) view.histogram = display_histogram(d.result, view.range);

  const Statistics& s = d.statistics;
  const auto length = [&](double x) { return fmt::format("{:.6g} ({:.4g}%)", x, 100 * x / report.diagonal); };
  const auto share = [&](std::size_t n) {
    return fmt::format("{} ({:.3g}%)", n, s.sample_count ? 100.0 * n / s.sample_count : 0.0);
  };
  view.figures = {{"USiAD (mean |d|)", length(s.usiad)},
                  {"SiAD (mean signed d)", length(s.siad)},
                  {"RMS", length(s.rms)},
                  {"STD (of signed d)", length(s.std_signed)},
                  {"max |d| (hits)", length(s.max_abs)},
                  {"|d| 95th percentile", length(s.p95)},
                  {"d > 0 (TEST outside)", share(signs.positive)},
                  {"d < 0 (TEST inside)", share(signs.negative)},
                  {"no hit within h", share(s.no_hit_count)}};
  if (d.intervals) {
    view.figures.push_back({"USiAD, 95% interval", fmt::format("[{:.6g}, {:.6g}]", d.intervals->usiad.lower,
                                                               d.intervals->usiad.upper)});
  }
  if (d.hausdorff) {
    view.figures.push_back({"Hausdorff, certified", fmt::format("[{:.6g}, {:.6g}]", d.hausdorff->lower, d.hausdorff->upper)});
  }
  view.figures.push_back({"query time", fmt::format("{:.3f} s", d.result.query_seconds)});
  view.figures.push_back({"colour range", "\u00b1" + length(view.range)});
  return view;
}

}  // namespace

HtmlPage measurement_page(const MeasureReport& report, const std::string& text, const nlohmann::json& json) {
  HtmlPage page;
  const DirectionReport& first = report.directions.front();
  page.title = fmt::format("{} {} {}: surface roving report", file_name(first.reference->path()),
                           report.symmetric() ? "and" : "against", file_name(first.test->path()));
  for (const DirectionReport& d : report.directions) page.views.push_back(direction_view(d, report));
  page.warnings = report.warnings;
  page.report_text = text;
  page.report = json;
  return page;
}

}  // namespace roving
