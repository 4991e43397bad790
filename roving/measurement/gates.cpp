// Parsing and checking --fail-above gates.
#include "gates.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "measure_report.h"
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

// Every value a gate can check: each direction's statistics, and the two-sided summary.
std::vector<MetricValue> gate_values(const MeasureReport& report) {
  std::vector<MetricValue> values;
  // The range of |mean| an interval [lower, upper] of a signed mean allows.
  const auto magnitudes = [](MetricValue& v, const MeanInterval& m) {
    v.low = m.lower <= 0 && 0 <= m.upper ? 0.0 : std::min(std::abs(m.lower), std::abs(m.upper));
    v.high = std::max(std::abs(m.lower), std::abs(m.upper));
  };
  for (const DirectionReport& d : report.directions) {
    const Statistics& s = d.statistics;
    const nlohmann::json statistics = statistics_json(s);
    for (const auto& [name, value] : statistics.items()) {
      MetricValue v{name, d.label, value.get<double>(), report.diagonal};
      if (d.intervals) {  // area:N samples: the plain and area-weighted means are the same estimate
        if (name == "siad" || name == "siad_area") magnitudes(v, d.intervals->siad);
        if (name == "usiad" || name == "usiad_area") magnitudes(v, d.intervals->usiad);
        if (name == "rms" || name == "rms_area") magnitudes(v, d.intervals->rms);
      }
      values.push_back(v);
    }
    values.push_back(
        {"no_hits", d.label, static_cast<double>(s.no_hit_count), static_cast<double>(s.sample_count)});
    if (d.colour) {
      // P% of a colour limit: of the peak (255) for an RMS, of L*'s range (100) for a delta E.
      const nlohmann::json colour = colour_json(*d.colour);
      for (const auto& [name, value] : colour.items()) {
        if (name.rfind("delta_e_", 0) == 0) values.push_back({name, d.label, value.get<double>(), 100.0});
        if (name == "colour_rms_y") values.push_back({name, d.label, value.get<double>(), kColourPeak});
      }
    }
  }
  if (report.mpeg) {  // MPEG's PSNRs, the worse direction's (--fail-below)
    const MpegFigures& f = report.mpeg->figures;
    const MpegDirection worse_direction = f.symmetric();
    values.push_back({"mpeg_d1_psnr", "", geometry_psnr(worse_direction.d1_mse, f.peak), 0});
    if (f.d2) values.push_back({"mpeg_d2_psnr", "", geometry_psnr(worse_direction.d2_mse, f.peak), 0});
    if (f.colour) values.push_back({"mpeg_y_psnr", "", colour_psnr(worse_direction.ycbcr_mse[0], 1), 0});
    if (report.mpeg->surface) {
      const SurfaceFigures both = worse((*report.mpeg->surface)[0], (*report.mpeg->surface)[1]);
      const auto psnr = [&](const char* name, double mse, const std::optional<Interval>& interval) {
        if (std::isnan(mse)) return;  // D2 without faces (a nearest-vertex method)
        MetricValue v{name, "", geometry_psnr(mse, f.peak), 0};
        if (interval) {
          v.low = geometry_psnr(interval->upper, f.peak);
          v.high = geometry_psnr(interval->lower, f.peak);
        }
        values.push_back(v);
      };
      psnr("mpeg_surface_d1_psnr", both.d1_mse, both.d1_mse_interval);
      psnr("mpeg_surface_d2_psnr", both.d2_mse, both.d2_mse_interval);
    }
  }
  if (report.symmetric()) {
    const TwoSided t = report.two_sided();
    MetricValue hausdorff{"hausdorff", "", t.max_abs, report.diagonal};
    if (t.certified) hausdorff.low = t.hausdorff_lower, hausdorff.high = t.hausdorff_upper;
    values.push_back(hausdorff);
    values.push_back({"mean_both", "", t.mean_abs, report.diagonal});
    values.push_back({"rms_both", "", t.rms, report.diagonal});
  }
  return values;
}

}  // namespace roving
