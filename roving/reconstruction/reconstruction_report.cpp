// The reconstruction figures' JSON section and text table (reconstruction_report.h).
#include "roving/reconstruction/reconstruction_report.h"

#include <fmt/format.h>

#include <cmath>

namespace roving {

void add_estimate(nlohmann::json& json, const std::string& key, const Estimate& e) {
  json[key] = e.value;
  if (!std::isnan(e.lower)) json[key + "_interval"] = {{"lower", e.lower}, {"upper", e.upper}};
}

std::string estimate_text(const Estimate& e) {
  return std::isnan(e.lower) ? fmt::format("{:.8g}", e.value)
                             : fmt::format("{:.8g} [{:.6g}, {:.6g}]", e.value, e.lower, e.upper);
}

nlohmann::json reconstruction_json(const ReconstructionFigures& f) {
  const auto direction = [](const DirectionFigures& d) {
    nlohmann::json json = {{"median", d.median}, {"hits", d.hits}, {"no_hits", d.no_hits}};
    add_estimate(json, "mean", d.mean);
    add_estimate(json, "rms", d.rms);
    add_estimate(json, "normal_consistency", d.normal_consistency);
    return json;
  };
  nlohmann::json json = {
      {"definition",
       "REF is the ground truth, TEST the reconstruction. accuracy: |d| of TEST's samples to REF (B -> A); "
       "completeness: REF's to TEST (A -> B); means, medians and RMS over the hits weighted by the area each "
       "sample stands for. chamfer_mean = (accuracy.mean + completeness.mean) / 2 (DTU's overall, Tanks and "
       "Temples); chamfer_sum = accuracy.mean + completeness.mean; chamfer_squared_mean = (accuracy.rms^2 + "
       "completeness.rms^2) / 2; chamfer_squared_sum = their sum. precision at tau: the share of TEST's area "
       "within tau of REF; recall: REF's within tau of TEST (a no-hit is beyond); f_score = 2 P R / (P + R). "
       "normal_consistency: mean |n . n'| of a sample's normal and the other surface's at the "
       "correspondence, "
       "each direction and their mean. *_interval (lower, upper): 95%, for area-uniform samples; "
       "chamfer_*_interval and f_score_interval combine the two directions' (independent samples: the delta "
       "method). "
       "*_certified (closest semantics between surfaces): the shares of area surely and possibly within tau, "
       "every point of the surfaces bounded, not sampled (docs/reconstruction.md); f_score_certified from "
       "them."},
      {"accuracy", direction(f.accuracy)},
      {"completeness", direction(f.completeness)},
      {"chamfer_mean", f.chamfer_mean},
      {"chamfer_sum", f.chamfer_sum},
      {"chamfer_squared_mean", f.chamfer_squared_mean},
      {"chamfer_squared_sum", f.chamfer_squared_sum},
      {"normal_consistency", f.normal_consistency},
      {"thresholds", nlohmann::json::array()}};
  const auto interval = [](const Estimate& e) {
    return nlohmann::json{{"lower", e.lower}, {"upper", e.upper}};
  };
  if (!std::isnan(f.chamfer_mean_estimate.lower)) {
    json["chamfer_mean_interval"] = interval(f.chamfer_mean_estimate);
    json["chamfer_sum_interval"] = interval(f.chamfer_sum_estimate);
  }
  const auto bounds = [](const ReconstructionFigures::Bounds& b) {
    return nlohmann::json{{"lower", b.lower}, {"upper", b.upper}};
  };
  for (std::size_t i = 0; i < f.thresholds.size(); ++i) {
    nlohmann::json row = {{"tau", f.thresholds[i]}, {"f_score", f.f_score[i]}};
    add_estimate(row, "precision", f.accuracy.within[i]);
    add_estimate(row, "recall", f.completeness.within[i]);
    if (!std::isnan(f.f_score_estimate[i].lower)) row["f_score_interval"] = interval(f.f_score_estimate[i]);
    if (!f.precision_certified.empty()) {
      row["precision_certified"] = bounds(f.precision_certified[i]);
      row["recall_certified"] = bounds(f.recall_certified[i]);
      row["f_score_certified"] = bounds(f.f_score_certified[i]);
    }
    json["thresholds"].push_back(row);
  }
  return json;
}

std::string reconstruction_lines(const ReconstructionFigures& f, double diagonal) {
  std::string out = fmt::format("\n  {:<40} {:>14} {:>12}\n", "reconstruction (REF the ground truth)",
                                "model units", "/ diagonal");
  const auto length = [&](const std::string& name, double value) {
    out += fmt::format("  {:<40} {:>14.6g} {:>12.6g}\n", name, value, value / diagonal);
  };
  length("accuracy, mean (TEST to REF)", f.accuracy.mean.value);
  length("accuracy, median", f.accuracy.median);
  length("completeness, mean (REF to TEST)", f.completeness.mean.value);
  length("completeness, median", f.completeness.median);
  length("Chamfer, mean of the two", f.chamfer_mean);
  if (!std::isnan(f.chamfer_mean_estimate.lower)) {
    out += fmt::format(
        "  {:<40} {:>14}\n", "  95% interval",
        fmt::format("[{:.6g}, {:.6g}]", f.chamfer_mean_estimate.lower, f.chamfer_mean_estimate.upper));
  }
  length("Chamfer, sum of the two", f.chamfer_sum);
  out += fmt::format("  {:<40} {:>14.6g}\n", "Chamfer, squared, mean of the two", f.chamfer_squared_mean);
  out += fmt::format("  {:<40} {:>14.6g}\n", "normal consistency", f.normal_consistency);
  for (std::size_t i = 0; i < f.thresholds.size(); ++i) {
    out += fmt::format(
        "  {:<40} {:>14}\n",
        fmt::format("at tau = {:.6g} ({:.3g}%)", f.thresholds[i], 100 * f.thresholds[i] / diagonal),
        fmt::format("P {:.4f} R {:.4f} F {:.4f}", f.precision[i], f.recall[i], f.f_score[i]));
    if (!std::isnan(f.f_score_estimate[i].lower)) {
      const Estimate &p = f.accuracy.within[i], &r = f.completeness.within[i], &q = f.f_score_estimate[i];
      out += fmt::format("  {:<40} {:>14}\n", "  95% intervals",
                         fmt::format("P [{:.4f}, {:.4f}] R [{:.4f}, {:.4f}] F [{:.4f}, {:.4f}]", p.lower,
                                     p.upper, r.lower, r.upper, q.lower, q.upper));
    }
    if (!f.precision_certified.empty()) {
      const auto& p = f.precision_certified[i];
      const auto& r = f.recall_certified[i];
      out += fmt::format(
          "  {:<40} {:>14}\n", "  certified (every point, not sampled)",
          fmt::format("P [{:.4f}, {:.4f}] R [{:.4f}, {:.4f}]", p.lower, p.upper, r.lower, r.upper));
    }
  }
  return out;
}

}  // namespace roving
