// The Tanks and Temples curves as the toolbox plots them (plot.py's plot_graph): the share of
// precision's and recall's distances below each distance, in %, over [0, tau * plot_stretch), tau
// dashed; beside them, where measured, the exact precision and recall at tau with their 95%
// intervals. Written as PNG by cairo.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace roving {

struct PrecisionRecallChart {
  std::string title, subtitle;
  double tau = 0, plot_stretch = 5;
  // edges[0] = 0; cumulative_*[i] is the share below edges[i + 1] (tanks_and_temples_protocol.h).
  std::vector<double> edges, cumulative_precision, cumulative_recall;
  struct Exact {
    double value = 0, lower = 0, upper = 0;  // shares; NaN bounds where none
  };
  std::optional<Exact> exact_precision, exact_recall;
};

// Throws roving::Error when cairo fails.
void write_precision_recall_png(std::FILE* out, const PrecisionRecallChart& chart);

}  // namespace roving
