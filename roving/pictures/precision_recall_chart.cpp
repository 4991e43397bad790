#include "roving/pictures/precision_recall_chart.h"

#include <cairo.h>
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "roving/core/error.h"

namespace roving {
namespace {

using Cairo = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using CairoSurface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

constexpr int kWidth = 900, kHeight = 560;
constexpr double kLeft = 80, kRight = 180, kTop = 70, kBottom = 70;  // margins around the plot

cairo_status_t write_to(void* file, const unsigned char* data, unsigned int length) {
  return std::fwrite(data, 1, length, static_cast<std::FILE*>(file)) == length ? CAIRO_STATUS_SUCCESS
                                                                               : CAIRO_STATUS_WRITE_ERROR;
}

void text(cairo_t* cr, double x, double y, double size, const std::string& s, double align = 0, bool bold = false) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_move_to(cr, x - align * extents.x_advance, y);
  cairo_show_text(cr, s.c_str());
}

struct Plot {
  double x_max;
  double px(double x) const { return kLeft + x / x_max * (kWidth - kLeft - kRight); }
  double py(double share) const { return kHeight - kBottom - share * (kHeight - kTop - kBottom); }
};

void curve(cairo_t* cr, const Plot& plot, const std::vector<double>& edges, const std::vector<double>& shares,
           double r, double g, double b) {
  if (shares.empty()) return;
  cairo_set_source_rgb(cr, r, g, b);
  cairo_set_line_width(cr, 2.5);
  cairo_move_to(cr, plot.px(edges[1]), plot.py(shares[0]));
  for (std::size_t i = 1; i < shares.size(); ++i) cairo_line_to(cr, plot.px(edges[i + 1]), plot.py(shares[i]));
  cairo_stroke(cr);
}

// The exact share at tau: a diamond, and its interval as a whisker.
void exact_marker(cairo_t* cr, const Plot& plot, double tau, const PrecisionRecallChart::Exact& e, double r, double g,
                  double b) {
  const double x = plot.px(tau), y = plot.py(e.value);
  cairo_set_source_rgb(cr, r, g, b);
  if (!std::isnan(e.lower)) {
    cairo_set_line_width(cr, 1.5);
    cairo_move_to(cr, x, plot.py(e.lower));
    cairo_line_to(cr, x, plot.py(e.upper));
    for (const double share : {e.lower, e.upper}) {
      cairo_move_to(cr, x - 5, plot.py(share));
      cairo_line_to(cr, x + 5, plot.py(share));
    }
    cairo_stroke(cr);
  }
  cairo_move_to(cr, x, y - 7);
  cairo_line_to(cr, x + 7, y);
  cairo_line_to(cr, x, y + 7);
  cairo_line_to(cr, x - 7, y);
  cairo_close_path(cr);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
}

void legend_line(cairo_t* cr, double x, double y, double r, double g, double b, const std::string& label, bool diamond) {
  cairo_set_source_rgb(cr, r, g, b);
  if (diamond) {
    cairo_move_to(cr, x + 14, y - 6);
    cairo_line_to(cr, x + 20, y);
    cairo_line_to(cr, x + 14, y + 6);
    cairo_line_to(cr, x + 8, y);
    cairo_close_path(cr);
    cairo_fill(cr);
  } else {
    cairo_set_line_width(cr, 2.5);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x + 28, y);
    cairo_stroke(cr);
  }
  text(cr, x + 36, y + 4, 12, label);
}

}  // namespace

void write_precision_recall_png(std::FILE* out, const PrecisionRecallChart& chart) {
  CairoSurface canvas(cairo_image_surface_create(CAIRO_FORMAT_RGB24, kWidth, kHeight), cairo_surface_destroy);
  Cairo cr(cairo_create(canvas.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  const Plot plot{chart.tau * chart.plot_stretch};
  // The grid: a line per tau across, per 20% up.
  cairo_set_source_rgb(cr.get(), 0.85, 0.85, 0.85);
  cairo_set_line_width(cr.get(), 1);
  const int x_ticks = static_cast<int>(std::floor(chart.plot_stretch + 1e-9));
  for (int k = 0; k <= x_ticks; ++k) {
    cairo_move_to(cr.get(), plot.px(k * chart.tau), plot.py(0));
    cairo_line_to(cr.get(), plot.px(k * chart.tau), plot.py(1));
  }
  for (int k = 0; k <= 5; ++k) {
    cairo_move_to(cr.get(), plot.px(0), plot.py(k / 5.0));
    cairo_line_to(cr.get(), plot.px(plot.x_max), plot.py(k / 5.0));
  }
  cairo_stroke(cr.get());
  cairo_set_source_rgb(cr.get(), 0.2, 0.2, 0.2);
  cairo_rectangle(cr.get(), plot.px(0), plot.py(1), plot.px(plot.x_max) - plot.px(0), plot.py(0) - plot.py(1));
  cairo_stroke(cr.get());
  for (int k = 0; k <= x_ticks; ++k) text(cr.get(), plot.px(k * chart.tau), plot.py(0) + 18, 12, fmt::format("{:.4g}", k * chart.tau), 0.5);
  for (int k = 0; k <= 5; ++k) text(cr.get(), plot.px(0) - 8, plot.py(k / 5.0) + 4, 12, fmt::format("{}", 20 * k), 1);
  text(cr.get(), (plot.px(0) + plot.px(plot.x_max)) / 2, kHeight - 22, 14, "distance (the models' units; metres for the benchmark)", 0.5);
  cairo_save(cr.get());
  cairo_translate(cr.get(), 26, (plot.py(0) + plot.py(1)) / 2);
  cairo_rotate(cr.get(), -M_PI / 2);
  text(cr.get(), 0, 0, 14, "points within the distance (%)", 0.5);
  cairo_restore(cr.get());
  text(cr.get(), kLeft, 28, 16, chart.title, 0, true);
  text(cr.get(), kLeft, 50, 12, chart.subtitle);
  // tau, dashed.
  const double dash[] = {8, 5};
  cairo_set_dash(cr.get(), dash, 2, 0);
  cairo_set_source_rgb(cr.get(), 0, 0, 0);
  cairo_set_line_width(cr.get(), 2);
  cairo_move_to(cr.get(), plot.px(chart.tau), plot.py(0));
  cairo_line_to(cr.get(), plot.px(chart.tau), plot.py(1));
  cairo_stroke(cr.get());
  cairo_set_dash(cr.get(), nullptr, 0, 0);
  cairo_save(cr.get());
  cairo_rectangle(cr.get(), plot.px(0), plot.py(1), plot.px(plot.x_max) - plot.px(0), plot.py(0) - plot.py(1));
  cairo_clip(cr.get());
  curve(cr.get(), plot, chart.edges, chart.cumulative_precision, 0.85, 0.1, 0.1);
  curve(cr.get(), plot, chart.edges, chart.cumulative_recall, 0.1, 0.2, 0.85);
  cairo_restore(cr.get());
  if (chart.exact_precision) exact_marker(cr.get(), plot, chart.tau, *chart.exact_precision, 1.0, 0.55, 0.55);
  if (chart.exact_recall) exact_marker(cr.get(), plot, chart.tau, *chart.exact_recall, 0.55, 0.65, 1.0);
  // The legend, right of the plot.
  const double lx = kWidth - kRight + 14;
  double ly = plot.py(0.75);
  legend_line(cr.get(), lx, ly, 0.85, 0.1, 0.1, "precision", false);
  legend_line(cr.get(), lx, ly += 22, 0.1, 0.2, 0.85, "recall", false);
  text(cr.get(), lx, ly += 22, 12, "- - tau");
  if (chart.exact_precision) {
    legend_line(cr.get(), lx, ly += 26, 1.0, 0.55, 0.55, "exact precision", true);
    legend_line(cr.get(), lx, ly += 22, 0.55, 0.65, 1.0, "exact recall", true);
    // Name the whisker only where one is drawn (an interval needs samples; some runs have none).
    const bool whiskers = !std::isnan(chart.exact_precision->lower) ||
                          (chart.exact_recall && !std::isnan(chart.exact_recall->lower));
    text(cr.get(), lx, ly += 20, 11, whiskers ? "at tau, 95% interval" : "at tau");
  }
  cairo_surface_flush(canvas.get());
  const cairo_status_t status = cairo_surface_write_to_png_stream(canvas.get(), write_to, out);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(fmt::format("precision and recall curves: writing the PNG failed: {}", cairo_status_to_string(status)));
  }
}

}  // namespace roving
