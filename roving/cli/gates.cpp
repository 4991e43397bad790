// Parsing and checking --fail-above gates.
#include "gates.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "report.h"
#include "roving/core/error.h"
#include "roving/formats/file_bytes.h"

namespace roving {

std::vector<std::string> gate_metrics(bool symmetric) {
  std::vector<std::string> names;
  const nlohmann::json statistics = statistics_json(Statistics());
  for (const auto& item : statistics.items()) names.push_back(item.key());
  names.push_back("no_hits");
  if (symmetric) names.insert(names.end(), {"hausdorff", "mean_both", "rms_both"});
  return names;
}

Gate parse_gate(const std::string& text, bool symmetric) {
  const auto fail = [&](const std::string& expected) {
    return Error(fmt::format("--fail-above: expected {}, found '{}'", expected, text));
  };
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) throw fail("METRIC=LIMIT (for example usiad=0.1%)");
  Gate gate;
  gate.text = text;
  gate.metric = text.substr(0, equals);
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

std::vector<std::string> breached_gates(const std::vector<Gate>& gates, const std::vector<MetricValue>& values) {
  std::vector<std::string> lines;
  for (const Gate& gate : gates) {
    for (const MetricValue& v : values) {
      if (v.metric != gate.metric) continue;
      const double limit = gate.percent ? gate.limit / 100 * v.percent_base : gate.limit;
      if (!(std::abs(v.value) <= limit)) {
        lines.push_back(fmt::format("gate breached: {}{} = {:.6g} is above the limit {:.6g} (--fail-above {})",
                                    gate.metric, v.where.empty() ? "" : " (" + v.where + ")", v.value, limit,
                                    gate.text));
      }
    }
  }
  return lines;
}

}  // namespace roving
