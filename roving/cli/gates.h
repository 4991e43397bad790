// Gates for a user's CI: `--fail-above METRIC=LIMIT`, the limit a length in model units or
// P% of the report's diagonal (no_hits: a count, or P% of the samples). A breached gate makes
// `roving` exit with kGateExitCode and print one line naming the metric, the limit and the value.
#pragma once

#include <string>
#include <vector>

namespace roving {

constexpr int kGateExitCode = 3;

struct Gate {
  std::string metric;
  double limit = 0;
  bool percent = false;
  std::string text;  // as given
};

// A measured value a gate can check. `where` says which direction it came from ("A -> B"), or
// is empty; `percent_base` is what P% is a percentage of (the diagonal, or the sample count).
struct MetricValue {
  std::string metric;
  std::string where;
  double value = 0;
  double percent_base = 0;
};

// The metrics a gate may name: the report's statistics, and with --symmetric the two-sided
// summary (hausdorff, mean_both, rms_both).
std::vector<std::string> gate_metrics(bool symmetric);

// Parses METRIC=VALUE or METRIC=P%; throws roving::Error naming --fail-above, what was
// expected and what was found.
Gate parse_gate(const std::string& text, bool symmetric);

// One line per breached gate and value: magnitudes are compared (a signed mean of -0.3
// breaches siad=0.2), and a metric measured in both directions is checked in each.
std::vector<std::string> breached_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values);

}  // namespace roving
