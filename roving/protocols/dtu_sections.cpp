// DTU's evaluation as the report shows it: its JSON section and its text (dtu_evaluation.h).
#include <fmt/format.h>

#include <cmath>

#include "roving/protocols/dtu_evaluation.h"
#include "roving/protocols/run_spread.h"
#include "roving/reconstruction/reconstruction_report.h"

namespace roving {
namespace {

constexpr std::array<std::pair<const char*, double DtuRun::*>, 3> kDtuFigures = {
    {{"accuracy", &DtuRun::accuracy},
     {"completeness", &DtuRun::completeness},
     {"overall", &DtuRun::overall}}};

std::string dtu_order(const DtuFigures& f) {
  if (!f.options.first_seed) return "the points' own order (eval.py with its shuffle left out)";
  const std::uint64_t first = *f.options.first_seed;
  return f.runs.size() == 1 ? fmt::format("shuffled with seed {}", first)
                            : fmt::format("shuffled with seeds {} to {}", first, first + f.runs.size() - 1);
}

// The exact figures where the protocol measures (null without --symmetric).
nlohmann::json dtu_exact_json(const DtuReport& d) {
  if (!d.exact) return nullptr;
  return {
      {"definition",
       "The exact figures (as under 'reconstruction') over the part of each surface the protocol measures: "
       "accuracy over TEST's samples inside BB - patch .. BB + 2 patch whose ObsMask voxel is observed, "
       "completeness over REF's samples above the plane P, measured against the whole other surface. "
       "figures: "
       "every distance counted; figures_below_max_dist: only the distances below max_dist, as the protocol "
       "counts them (what the cap hides is the difference)"},
      {"test_samples_counted", d.exact_test_counted},
      {"test_samples", d.exact_test_samples},
      {"reference_samples_counted", d.exact_reference_counted},
      {"reference_samples", d.exact_reference_samples},
      {"figures", reconstruction_json(*d.exact)},
      {"figures_below_max_dist", reconstruction_json(*d.exact_below_cap)}};
}

}  // namespace

nlohmann::json dtu_json(const DtuReport& d) {
  const DtuFigures& f = d.figures;
  const DtuRun& first = f.runs.front();
  nlohmann::json runs = nlohmann::json::array();
  for (const DtuRun& r : f.runs) {
    runs.push_back({{"seed", r.seed ? nlohmann::json(*r.seed) : nlohmann::json(nullptr)},
                    {"accuracy", r.accuracy},
                    {"completeness", r.completeness},
                    {"overall", r.overall},
                    {"thinned", r.thinned},
                    {"in_box", r.in_box},
                    {"observed", r.observed},
                    {"accuracy_counted", r.accuracy_counted},
                    {"completeness_counted", r.completeness_counted}});
  }
  return {
      {"definition",
       "DTU MVS evaluation as DTUeval-python's eval.py computes it: TEST sampled (a mesh: its vertices, then "
       "per face a grid of step density scaled to its shape) or read (points), shuffled, thinned to no two "
       "points within density, kept inside BB - patch .. BB + 2 patch; accuracy = mean distance from the "
       "kept points inside ObsMask to REF's nearest point, completeness = mean distance from REF's points "
       "above the plane P to the kept points' nearest, each over the distances below max_dist; overall = "
       "(accuracy + completeness) / 2. See docs/reconstruction.md"},
      {"computed_as", "DTUeval-python eval.py (github.com/jzhangbs/DTUeval-python, 45b4fec), step by step"},
      {"obs_mask", d.obs_mask},
      {"plane", d.plane},
      {"density", f.options.density},
      {"patch", f.options.patch},
      {"max_dist", f.options.max_dist},
      {"order", dtu_order(f)},
      {"reconstruction_points", f.reconstruction_points},
      {"samples", f.samples},
      {"ground_truth_points", f.ground_truth_points},
      {"ground_truth_above", f.ground_truth_above},
      {"seed", first.seed ? nlohmann::json(*first.seed) : nlohmann::json(nullptr)},
      {"accuracy", first.accuracy},
      {"completeness", first.completeness},
      {"overall", first.overall},
      {"runs", runs},
      {"spread", spread_json(f.runs, kDtuFigures)},
      {"exact_within_region", dtu_exact_json(d)},
      {"seconds", d.seconds}};
}

std::string dtu_lines(const DtuReport& d) {
  const DtuFigures& f = d.figures;
  const DtuRun& first = f.runs.front();
  std::string out = fmt::format(
      "\n  DTU protocol (DTUeval-python's eval.py): density {:.6g}, patch {:.6g}, max_dist {:.6g}; {}\n",
      f.options.density, f.options.patch, f.options.max_dist, dtu_order(f));
  out += fmt::format(
      "  reconstruction {} points ({} sampled from faces); ground truth {} points, {} above the plane\n",
      f.reconstruction_points, f.samples, f.ground_truth_points, f.ground_truth_above);
  const std::string first_label = first.seed ? fmt::format("seed {}", *first.seed) : std::string("own order");
  out += fmt::format("  {:<14} {:>14}", "figure", first_label);
  if (f.runs.size() > 1)
    out += fmt::format(" {:>30} {:>28}", fmt::format("mean +- sd over {} runs", f.runs.size()), "[min, max]");
  out += "\n";
  for (const auto& [name, figure] : kDtuFigures) {
    out += fmt::format("  {:<14} {:>14.8g}", name, first.*figure);
    if (f.runs.size() > 1) {
      const Spread s = spread_of(f.runs, figure);
      out += fmt::format(" {:>30} {:>28}", fmt::format("{:.8g} +- {:.2g}", s.mean, s.sd),
                         fmt::format("[{:.8g}, {:.8g}]", s.min, s.max));
    }
    out += "\n";
  }
  out += fmt::format(
      "  ({}: {} points after thinning, {} in the box, {} observed; below max_dist: {} of the observed, {} "
      "of the "
      "ground truth above the plane)\n",
      first_label, first.thinned, first.in_box, first.observed, first.accuracy_counted,
      first.completeness_counted);
  if (d.exact) {
    const ReconstructionFigures &e = *d.exact, &capped = *d.exact_below_cap;
    out += fmt::format(
        "  exact, where the protocol measures (TEST's samples observed: {} of {}; REF's above the plane: {} "
        "of {}):\n",
        d.exact_test_counted, d.exact_test_samples, d.exact_reference_counted, d.exact_reference_samples);
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "figure", "every distance [95%]", "below max_dist [95%]");
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "accuracy", estimate_text(e.accuracy.mean),
                       estimate_text(capped.accuracy.mean));
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "completeness", estimate_text(e.completeness.mean),
                       estimate_text(capped.completeness.mean));
    out += fmt::format("  {:<14} {:>40} {:>40}\n", "overall", estimate_text(e.chamfer_mean_estimate),
                       estimate_text(capped.chamfer_mean_estimate));
    out += fmt::format("  (below max_dist: {} of TEST's observed samples, {} of REF's above the plane)\n",
                       capped.accuracy.hits, capped.completeness.hits);
  }
  return out;
}

}  // namespace roving
