// Gates for a user's CI: `--fail-above METRIC=LIMIT`, the limit a length in model units or
// P% of the report's diagonal (no_hits: a count, or P% of the samples); `--fail-below
// METRIC=FLOOR` for figures where more is better (MPEG's PSNRs, in dB). A breached gate makes
// `roving` exit with kGateExitCode and print one line naming the metric, the limit and the value.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace roving {

constexpr int kGateExitCode = 3;

struct Gate {
  std::string metric;
  double limit = 0;
  bool percent = false;
  bool floor = false;  // --fail-below: breached below the limit
  std::string text;    // as given
  std::string option() const { return floor ? "--fail-below" : "--fail-above"; }
};

// A measured value a gate can check. `where` says which direction it came from ("A -> B"), or
// is empty; `percent_base` is what P% is a percentage of (the diagonal, or the sample count).
struct MetricValue {
  std::string metric;
  std::string where;
  double value = 0;
  double percent_base = 0;
  // Where the value is uncertain: the range of its magnitude that the interval allows (a 95%
  // sampling interval, or the certified Hausdorff interval); both NaN otherwise.
  double low = std::nan(""), high = std::nan("");
};

// What a gate compares with its limit: the estimate, or the upper end of its interval.
enum class GateOn { Estimate, Upper };

// The metrics a gate may name: the report's statistics, the colour figures (delta_e_mean,
// delta_e_p95, delta_e_max: CIEDE2000, P% of L*'s range 100; colour_rms_y: RMS of Y' in code
// values, P% of the peak 255), and with --symmetric the two-sided summary (hausdorff, mean_both,
// rms_both).
std::vector<std::string> gate_metrics(bool symmetric);

// The metrics --fail-below may name: MPEG's symmetric (worse-direction) D1, D2 and Y PSNR, and the
// surfaces' own D1 PSNR (two meshes under --pcc), in dB.
std::vector<std::string> floor_metrics();

// Parses METRIC=VALUE or METRIC=P% (a floor: METRIC=dB); throws roving::Error naming the option,
// what was expected and what was found.
Gate parse_gate(const std::string& text, bool symmetric, bool floor = false);

// True for the colour figures' names (delta_e_*, colour_rms_y).
bool is_colour_metric(const std::string& metric);

// Throws roving::Error naming the gate when no measured value is of its metric (a colour gate on
// models without colour), so that a gate never passes for want of a figure.
void require_gate_values(const std::vector<Gate>& gates, const std::vector<MetricValue>& values);

// One line per breached gate and value: magnitudes are compared (a signed mean of -0.3
// breaches siad=0.2), and a metric measured in both directions is checked in each.
// Under GateOn::Upper a value with an interval is compared by its interval's upper end (a floor
// by its lower end).
std::vector<std::string> breached_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values,
                                        GateOn on = GateOn::Estimate);

// One line per gate whose decision rests inside an interval (its limit lies between the interval's
// ends, so other samples could decide the other way), or whose figure passes while its whole
// interval does not (a sampled Hausdorff distance below the certified one).
std::vector<std::string> undecided_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values);

// The gates as measure and merge apply them: the undecided ones as notes (gating on the
// estimate) and the breached ones on stderr; returns 0, or kGateExitCode when one is breached.
int apply_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values, GateOn on);

struct MeasureReport;  // measure_report.h

// Every value a --fail-above gate can check: each direction's statistics, and the two-sided
// summary.
std::vector<MetricValue> gate_values(const MeasureReport& report);

}  // namespace roving
