// Minimal SVG line charts for the report's figures (histograms, H x V trade-offs).
#pragma once

#include <string>
#include <vector>

namespace roving {

struct ChartSeries {
  std::string name, colour;
  std::vector<double> x, y;
};

// A line chart with axes, ticks, labels and a legend; `log_y` plots log10(y) (y > 0 only).
std::string line_chart_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                           const std::vector<ChartSeries>& series, bool log_y = false);

}  // namespace roving
