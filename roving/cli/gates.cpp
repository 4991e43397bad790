// Parsing and checking --fail-above gates.
#include "gates.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report.h"
#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {

std::vector<std::string> gate_metrics(bool symmetric) {
  std::vector<std::string> names;
  const nlohmann::json statistics = statistics_json(Statistics());
  for (const auto& item : statistics.items()) names.push_back(item.key());
  names.push_back("no_hits");
  names.insert(names.end(), {"delta_e_mean", "delta_e_p95", "delta_e_max", "colour_rms_y"});
  if (symmetric) names.insert(names.end(), {"hausdorff", "mean_both", "rms_both"});
  return names;
}

std::vector<std::string> floor_metrics() {
  return {"mpeg_d1_psnr", "mpeg_d2_psnr", "mpeg_y_psnr", "mpeg_surface_d1_psnr", "mpeg_surface_d2_psnr"};
}

Gate parse_gate(const std::string& text, bool symmetric, bool floor) {
  const auto fail = [&](const std::string& expected) {
    return Error(fmt::format("{}: expected {}, found '{}'", floor ? "--fail-below" : "--fail-above", expected, text));
  };
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    throw fail(floor ? "METRIC=FLOOR (for example mpeg_d1_psnr=60)" : "METRIC=LIMIT (for example usiad=0.1%)");
  }
  Gate gate;
  gate.text = text;
  gate.floor = floor;
  gate.metric = text.substr(0, equals);
  if (floor) {
    const auto names = floor_metrics();
    if (std::find(names.begin(), names.end(), gate.metric) == names.end()) {
      throw fail(fmt::format("a metric among {}", fmt::join(names, ", ")));
    }
    if (!parse_number(std::string_view(text).substr(equals + 1), gate.limit) || !std::isfinite(gate.limit)) {
      throw fail(fmt::format("a PSNR floor in dB after '{}='", gate.metric));
    }
    return gate;
  }
  const auto names = gate_metrics(symmetric);
  if (std::find(names.begin(), names.end(), gate.metric) == names.end()) {
    const bool two_sided = gate.metric == "hausdorff" || gate.metric == "mean_both" || gate.metric == "rms_both";
    throw fail(fmt::format("a metric among {}{}", fmt::join(names, ", "),
                           two_sided ? " ('" + gate.metric + "' needs --symmetric)" : ""));
  }
  std::string_view value = std::string_view(text).substr(equals + 1);
  gate.percent = !value.empty() && value.back() == '%';
  if (gate.percent) value.remove_suffix(1);
  if (!parse_number(value, gate.limit) || !std::isfinite(gate.limit) || gate.limit < 0 ||
      (gate.percent && gate.limit > 100)) {
    throw fail(fmt::format("a limit >= 0 after '{}=': a length, or P% with P in [0, 100]", gate.metric));
  }
  return gate;
}

bool is_colour_metric(const std::string& metric) {
  return metric.rfind("delta_e_", 0) == 0 || metric == "colour_rms_y";
}

void require_gate_values(const std::vector<Gate>& gates, const std::vector<MetricValue>& values) {
  for (const Gate& gate : gates) {
    const bool measured = std::any_of(values.begin(), values.end(),
                                      [&](const MetricValue& v) { return v.metric == gate.metric; });
    if (!measured) {
      throw Error(fmt::format(
          "{} {}: nothing measured gives '{}' ({})", gate.option(), gate.text, gate.metric,
          gate.floor ? "MPEG's figures need two point clouds, or --pcc; D2 normals on A; Y colour on both; the "
                       "surfaces' D1 and D2 two meshes under --pcc"
                     : "colour figures need vertex colours on both meshes and --method embree or cgal"));
    }
  }
}

namespace {

double limit_of(const Gate& gate, const MetricValue& v) {
  return gate.percent ? gate.limit / 100 * v.percent_base : gate.limit;
}

std::string where(const MetricValue& v) {
  return v.where.empty() ? "" : " (" + v.where + ")";
}

}  // namespace

std::vector<std::string> breached_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values,
                                        GateOn on) {
  std::vector<std::string> lines;
  for (const Gate& gate : gates) {
    for (const MetricValue& v : values) {
      if (v.metric != gate.metric) continue;
      const double limit = limit_of(gate, v);
      if (gate.floor) {  // a PSNR: more is better; an infinite one (identical) passes
        const bool lower = on == GateOn::Upper && !std::isnan(v.low);
        const double compared = lower ? v.low : v.value;
        if (!(compared >= limit)) {
          lines.push_back(fmt::format("gate breached: {}{} = {:.6g} dB{} is below the floor {:.6g} dB (--fail-below {})",
                                      gate.metric, where(v), v.value,
                                      lower ? fmt::format(", its interval reaching down to {:.6g},", v.low) : "",
                                      limit, gate.text));
        }
        continue;
      }
      const bool upper = on == GateOn::Upper && !std::isnan(v.high);
      const double compared = upper ? v.high : std::abs(v.value);
      if (std::isnan(compared)) {  // fails closed: a figure that could not be measured passes no gate
        lines.push_back(
            fmt::format("gate breached: {}{} has no value (nothing was compared) (--fail-above {})",
                        gate.metric, where(v), gate.text));
      } else if (!(compared <= limit)) {
        lines.push_back(fmt::format("gate breached: {}{} = {:.6g}{} is above the limit {:.6g} (--fail-above {})",
                                    gate.metric, where(v), v.value,
                                    upper ? fmt::format(", its interval reaching {:.6g},", v.high) : "", limit,
                                    gate.text));
      }
    }
  }
  return lines;
}

std::vector<std::string> undecided_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values) {
  std::vector<std::string> lines;
  for (const Gate& gate : gates) {
    for (const MetricValue& v : values) {
      const double limit = limit_of(gate, v);
      if (v.metric != gate.metric || std::isnan(v.low)) continue;
      if (gate.floor) {
        if (v.low < limit && limit < v.high) {
          lines.push_back(fmt::format(
              "gate {}{}: the floor {:.6g} dB lies inside the interval [{:.6g}, {:.6g}] of {:.6g}: the decision "
              "rests on sampling (more samples narrow it; --gate-on upper decides on the interval's lower end)",
              gate.metric, where(v), limit, v.low, v.high, v.value));
        }
        continue;
      }
      if (std::abs(v.value) <= limit && limit <= v.low) {  // a sampled maximum below a certified interval
        lines.push_back(fmt::format(
            "gate {}{}: {:.6g} passes the limit {:.6g}, but the interval [{:.6g}, {:.6g}] lies wholly above it: the "
            "samples missed the farthest points (--gate-on upper decides on the interval)",
            gate.metric, where(v), std::abs(v.value), limit, v.low, v.high));
        continue;
      }
      if (!(v.low < limit && limit < v.high)) continue;
      lines.push_back(fmt::format(
          "gate {}{}: the limit {:.6g} lies inside the interval [{:.6g}, {:.6g}] of {:.6g}: the decision rests on "
          "sampling (more samples narrow it; --gate-on upper decides on the interval's upper end)",
          gate.metric, where(v), limit, v.low, v.high, std::abs(v.value)));
    }
  }
  return lines;
}

int apply_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values, GateOn on) {
  if (on == GateOn::Estimate) {
    for (const std::string& line : undecided_gates(gates, values)) std::fprintf(stderr, "roving: note: %s\n", line.c_str());
  }
  const std::vector<std::string> breached = breached_gates(gates, values, on);
  for (const std::string& line : breached) std::fprintf(stderr, "roving: %s\n", line.c_str());
  return breached.empty() ? 0 : kGateExitCode;
}

}  // namespace roving
