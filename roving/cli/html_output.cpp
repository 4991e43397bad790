// The measurement page's contents, from the report.
#include "html_output.h"

#include <fmt/format.h>

#include <filesystem>

#include "measure.h"
#include "roving/formats/heatmap.h"
#include "roving/html/distance_view.h"

namespace roving {
namespace {

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

HtmlView direction_view(const DirectionReport& d, const MeasureReport& report) {
  const Model& reference = *d.reference;
  const TriangleMesh* surface = reference.type == ModelType::Points ? nullptr : &reference.mesh.mesh;
  HtmlView view = distance_view(surface, heatmap_layout(reference, d.samples), d.samples, d.result, d.statistics,
                                d.heatmap_range, report.diagonal, report.max_error);
  view.label = d.label;
  view.title = fmt::format("{} (REF) against {} (TEST){}", file_name(reference.path()), file_name(d.test->path()),
                           d.label.empty() ? "" : ", " + d.label);
  view.subtitle = fmt::format("d by {}, {} semantics, {} samples ({}), h = {:.4g}", report.method,
                              to_string(report.semantics), d.samples.size(), d.samples.kind, report.max_error);
  view.method = report.method;
  // Before the last two rows (query time, colour range): the intervals where there are some.
  const auto at = view.figures.end() - 2;
  std::vector<std::pair<std::string, std::string>> intervals;
  if (d.intervals) {
    intervals.push_back({"USiAD, 95% interval", fmt::format("[{:.6g}, {:.6g}]", d.intervals->usiad.lower,
                                                            d.intervals->usiad.upper)});
  }
  if (d.hausdorff) {
    intervals.push_back({"Hausdorff, certified", fmt::format("[{:.6g}, {:.6g}]", d.hausdorff->lower, d.hausdorff->upper)});
  }
  view.figures.insert(at, intervals.begin(), intervals.end());
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
