// SVG line charts written by hand: a few dozen elements, no library needed.
#include "svg_chart.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace roving {

std::string line_chart_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                           const std::vector<ChartSeries>& series, bool log_y) {
  const double width = 820, height = 440, left = 100, right = 240, top = 44, bottom = 60;
  const auto ty = [&](double y) { return log_y ? std::log10(y) : y; };
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (log_y && !(s.y[i] > 0)) continue;
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, ty(s.y[i])), y1 = std::max(y1, ty(s.y[i]));
    }
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;
  if (!log_y) y0 = std::min(y0, 0.0);
  const double pad = 0.05 * (y1 - y0);
  y1 += pad;
  const auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (width - left - right); };
  const auto py = [&](double y) {
    return height - bottom - (ty(y) - y0) / (y1 - y0) * (height - top - bottom);
  };
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" font-family=\"sans-serif\" "
      "font-size=\"12\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n"
      "<text x=\"{2}\" y=\"24\" font-size=\"15\">{3}</text>\n",
      width, height, left, title);
  svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\"/>\n", left,
                     height - bottom, width - right);
  svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"black\"/>\n", left, top,
                     height - bottom);
  for (int i = 0; i <= 5; ++i) {
    const double x = x0 + (x1 - x0) * i / 5, yv = y0 + (y1 - y0) * i / 5;
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{:.3g}</text>\n", px(x),
                       height - bottom + 18, x);
    const double y_shown = log_y ? std::pow(10, yv) : yv;
    const double y_pixel = height - bottom - (yv - y0) / (y1 - y0) * (height - top - bottom);
    svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{:.3g}</text>\n", left - 6, y_pixel + 4,
                       y_shown);
    svg += fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#ddd\"/>\n", left, y_pixel,
                       width - right, y_pixel);
  }
  svg += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", (left + width - right) / 2,
                     height - 15, x_label);
  svg += fmt::format(
      "<text x=\"16\" y=\"{0}\" transform=\"rotate(-90 16 {0})\" text-anchor=\"middle\">{1}{2}</text>\n",
      (top + height - bottom) / 2, y_label, log_y ? " (log scale)" : "");
  for (std::size_t s = 0; s < series.size(); ++s) {
    std::string points;
    for (std::size_t i = 0; i < series[s].x.size(); ++i) {
      if (log_y && !(series[s].y[i] > 0)) continue;
      points += fmt::format("{:.1f},{:.1f} ", px(series[s].x[i]), py(series[s].y[i]));
    }
    // Overlapping series stay visible: the first wide and solid, the next dashed, then dotted.
    static const char* const kDash[] = {"none", "8 4", "2 3", "12 3 2 3"};
    static const double kWidth[] = {4.5, 2.2, 2.2, 2.2};
    svg += fmt::format(
        "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-dasharray=\"{}\" points=\"{}\"/>\n",
        series[s].colour, kWidth[s % 4], kDash[s % 4], points);
    const double ly = top + 10 + 20.0 * s;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"{3}\" stroke-width=\"3\" "
        "stroke-dasharray=\"{7}\"/>"
        "<text x=\"{4}\" y=\"{5}\">{6}</text>\n",
        width - right + 10, ly, width - right + 30, series[s].colour, width - right + 35, ly + 4,
        series[s].name, kDash[s % 4]);
  }
  return svg + "</svg>\n";
}

}  // namespace roving
