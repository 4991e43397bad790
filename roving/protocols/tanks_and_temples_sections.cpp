// Tanks and Temples' evaluation as the report shows it: its JSON section and its text
// (tanks_and_temples_evaluation.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "roving/protocols/run_spread.h"
#include "roving/protocols/tanks_and_temples_evaluation.h"
#include "roving/reconstruction/reconstruction_report.h"

namespace roving {
namespace {

std::string tnt_tau_source(const TanksAndTemplesReport& t) {
  return t.scene.empty() ? std::string("as given by --tnt-tau")
                         : fmt::format("{}'s, as the toolbox's config.py sets it", t.scene);
}

nlohmann::json matrix_json(const Eigen::Matrix4d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return rows;
}

constexpr std::array<std::pair<const char*, double TanksAndTemplesRegistrationRun::*>, 3> kTntFigures = {
    {{"precision", &TanksAndTemplesRegistrationRun::precision},
     {"recall", &TanksAndTemplesRegistrationRun::recall},
     {"fscore", &TanksAndTemplesRegistrationRun::fscore}}};

// run.py's registration, per run (null where the alignment was given).
nlohmann::json tnt_registration_json(const TanksAndTemplesReport& t) {
  if (t.registrations.empty()) return nullptr;
  nlohmann::json runs = nlohmann::json::array();
  for (const TanksAndTemplesRegistrationRun& run : t.registrations) {
    const TanksAndTemplesRegistration& r = run.registration;
    nlohmann::json rounds = nlohmann::json::array();
    for (const TanksAndTemplesRegistration::Round& round : r.rounds) {
      rounds.push_back(
          {{"voxel_size", round.voxel_size > 0 ? nlohmann::json(round.voxel_size) : nlohmann::json(nullptr)},
           {"max_distance", round.max_distance},
           {"source_points", round.source_points},
           {"target_points", round.target_points},
           {"fitness", round.icp.fitness},
           {"inlier_rmse", round.icp.inlier_rmse},
           {"iterations", round.icp.iterations},
           {"transformation", matrix_json(round.transformation)}});
    }
    runs.push_back({{"seed", r.seed},
                    {"cameras",
                     {{"fitness", r.trajectory.fitness},
                      {"inlier_rmse", r.trajectory.inlier_rmse},
                      {"transformation", matrix_json(r.trajectory.transformation)}}},
                    {"rounds", rounds},
                    {"transformation", matrix_json(r.transformation)},
                    {"precision", run.precision},
                    {"recall", run.recall},
                    {"fscore", run.fscore},
                    {"reported", run.reported}});
  }
  return {
      {"definition",
       "run.py's registration before EvaluateHisto: the reconstruction's camera centres (those the mapping "
       "names where there are more than 1,600) aligned to the scene's (COLMAP's, moved by alignment_file) by "
       "RANSAC (6 pairs a draw, pairs closer than 0.2, confidence 0.999, draws from the seed), then ICP "
       "point to point with scale in three rounds on both clouds cropped: voxels of tau and pairs within 80 "
       "tau, voxels of tau / 2 and 20 tau, uniform (every k-th point above 4 M) and 2 tau, each round "
       "stopping "
       "once its fitness changes by less than 1e-6 (ICPConvergenceCriteria(1e-6, 20): the RMSE's criterion "
       "is 20) or after 30 updates. Each run's transformation is the product of the rounds' and RANSAC's; "
       "the run marked reported gives 'alignment' and the figures above: the run whose figures the most runs "
       "give, the earliest of them (run.py draws unseeded: where it gives one result nearly every time, most "
       "seeds give it too); spread: over the runs' seeds"},
      {"trajectory", t.trajectory},
      {"reference_trajectory", t.reference_trajectory},
      {"mapping", t.mapping.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.mapping)},
      {"cameras", reported_run(t.registrations).registration.cameras},
      {"runs", runs},
      {"spread", spread_json(t.registrations, kTntFigures)},
      {"seconds", t.registration_seconds}};
}

}  // namespace

nlohmann::json tnt_json(const TanksAndTemplesReport& t) {
  const TanksAndTemplesFigures& f = t.figures;
  nlohmann::json exact = nullptr;
  if (t.exact) {
    exact = {{"definition",
              "The exact figures (as under 'reconstruction', the first threshold tau) over the part of each "
              "surface "
              "inside the crop volume: precision's side (accuracy) over TEST's aligned samples inside it, "
              "recall's "
              "(completeness) over REF's, each measured against the whole other surface, neither thinned"},
             {"test_samples_counted", t.exact_test_counted},
             {"test_samples", t.exact_test_samples},
             {"reference_samples_counted", t.exact_reference_counted},
             {"reference_samples", t.exact_reference_samples},
             {"figures", reconstruction_json(*t.exact)}};
  }
  return {
      {"definition",
       "Tanks and Temples evaluation as its toolbox's EvaluateHisto computes it: TEST (its points, or a "
       "mesh's "
       "vertices) moved by the alignment, both clouds cropped to the crop volume and voxel down-sampled at "
       "voxel_size (each occupied cube's mean point); precision = share of TEST's points whose nearest REF "
       "point is closer than tau, recall = share of REF's points closer than tau to TEST's nearest, fscore = "
       "2 precision recall / (precision + recall); cumulative_precision[i] and cumulative_recall[i] = share "
       "of "
       "the distances below edges[i + 1] (at or below, for the last), edges = np.arange(0, tau * "
       "plot_stretch, "
       "tau / 100). See docs/reconstruction.md"},
      {"computed_as",
       t.registrations.empty()
           ? "TanksAndTemples python_toolbox/evaluation (github.com/isl-org/TanksAndTemples, 3c2c212), "
             "EvaluateHisto step by step on Open3D 0.16's operations; run.py's registration (RANSAC and ICP) "
             "not "
             "run: the alignment is the one given"
           : "TanksAndTemples python_toolbox/evaluation (github.com/isl-org/TanksAndTemples, 3c2c212), "
             "run.py "
             "step by step on Open3D 0.16's operations: its registration (RANSAC from the seed, as Open3D on "
             "one thread after utility.random.seed) and EvaluateHisto"},
      {"scene", t.scene.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.scene)},
      {"tau", f.options.tau},
      {"tau_source", tnt_tau_source(t)},
      {"voxel_size", f.options.voxel_size},
      {"plot_stretch", f.options.plot_stretch},
      {"crop", t.crop},
      {"alignment_file", t.alignment.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.alignment)},
      {"alignment", matrix_json(t.alignment_matrix)},
      {"registration", tnt_registration_json(t)},
      {"reconstruction_points", f.reconstruction_points},
      {"reconstruction_cropped", f.reconstruction_cropped},
      {"reconstruction_thinned", f.reconstruction_thinned},
      {"ground_truth_points", f.ground_truth_points},
      {"ground_truth_cropped", f.ground_truth_cropped},
      {"ground_truth_thinned", f.ground_truth_thinned},
      {"precision_counted", f.precision_counted},
      {"recall_counted", f.recall_counted},
      {"precision", f.precision},
      {"recall", f.recall},
      {"fscore", f.fscore},
      {"edges", f.edges},
      {"cumulative_precision", f.cumulative_precision},
      {"cumulative_recall", f.cumulative_recall},
      {"curves_png", t.curves_png.empty() ? nlohmann::json(nullptr) : nlohmann::json(t.curves_png)},
      {"plys", t.plys.empty() ? nlohmann::json(nullptr)
                              : nlohmann::json({t.plys + ".precision.ply", t.plys + ".recall.ply"})},
      {"exact_within_crop", exact},
      {"seconds", t.seconds}};
}

std::string tnt_lines(const TanksAndTemplesReport& t) {
  const TanksAndTemplesFigures& f = t.figures;
  std::string out = fmt::format(
      "\n  Tanks and Temples protocol (the toolbox's EvaluateHisto): tau {:.6g} ({}), voxel size {:.6g}, "
      "crop {}, "
      "alignment {}\n",
      f.options.tau, tnt_tau_source(t), f.options.voxel_size, t.crop,
      t.registrations.empty() ? (t.alignment.empty() ? "none" : t.alignment)
                              : fmt::format("run.py's registration from {}", t.alignment));
  if (!t.registrations.empty()) {
    const TanksAndTemplesRegistration& r = reported_run(t.registrations).registration;
    const auto same = static_cast<std::size_t>(std::count_if(
        t.registrations.begin(), t.registrations.end(), [&](const TanksAndTemplesRegistrationRun& run) {
          return run.fscore == t.figures.fscore && run.precision == t.figures.precision && run.recall == t.figures.recall;
        }));
    out += fmt::format(
        "  registration ({:.3g} s): RANSAC on {} cameras of {} (seed {}{}): fitness {:.6g}, RMSE {:.6g}\n",
        t.registration_seconds, r.cameras, t.trajectory, r.seed,
        t.registrations.size() > 1 ? fmt::format(", whose figures {} of {} seeds give", same, t.registrations.size())
                                   : "",
        r.trajectory.fitness, r.trajectory.inlier_rmse);
    for (std::size_t k = 0; k < r.rounds.size(); ++k) {
      const TanksAndTemplesRegistration::Round& round = r.rounds[k];
      out += fmt::format(
          "    ICP round {} ({}, pairs within {:.6g}): {} TEST and {} REF points, fitness {:.6g}, "
          "RMSE {:.6g} after {} update{}\n",
          k + 1, round.voxel_size > 0 ? fmt::format("voxels of {:.6g}", round.voxel_size) : "uniform",
          round.max_distance, round.source_points, round.target_points, round.icp.fitness,
          round.icp.inlier_rmse, round.icp.iterations, round.icp.iterations == 1 ? "" : "s");
    }
  }
  out += fmt::format(
      "  reconstruction {} points, {} in the crop, {} after down-sampling; ground truth {}, {}, {}\n",
      f.reconstruction_points, f.reconstruction_cropped, f.reconstruction_thinned, f.ground_truth_points,
      f.ground_truth_cropped, f.ground_truth_thinned);
  out += fmt::format("  {:<14} {:>14} {:>28}\n", "figure", "protocol", "points below tau");
  out += fmt::format("  {:<14} {:>14.8g} {:>28}\n", "precision", f.precision,
                     fmt::format("{} of {}", f.precision_counted, f.reconstruction_thinned));
  out += fmt::format("  {:<14} {:>14.8g} {:>28}\n", "recall", f.recall,
                     fmt::format("{} of {}", f.recall_counted, f.ground_truth_thinned));
  out += fmt::format("  {:<14} {:>14.8g}\n", "F-score", f.fscore);
  if (t.registrations.size() > 1) {
    out += fmt::format("  {:<14} {:>47} {:>28}\n",
                       fmt::format("seeds {} to {}", t.registrations.front().registration.seed,
                                   t.registrations.back().registration.seed),
                       fmt::format("mean +- sd over {} registrations", t.registrations.size()), "[min, max]");
    for (const auto& [name, figure] : kTntFigures) {
      const Spread s = spread_of(t.registrations, figure);
      out += fmt::format("  {:<14} {:>47} {:>28}\n", std::string(name) == "fscore" ? "F-score" : name,
                         fmt::format("{:.8g} +- {:.2g}", s.mean, s.sd),
                         fmt::format("[{:.8g}, {:.8g}]", s.min, s.max));
    }
  }
  if (!t.curves_png.empty()) out += fmt::format("  curves: {}\n", t.curves_png);
  if (!t.plys.empty()) {
    out += fmt::format("  coloured by distance (hot_r up to 3 tau): {0}.precision.ply, {0}.recall.ply\n",
                       t.plys);
  }
  if (t.exact) {
    const ReconstructionFigures& e = *t.exact;
    out += fmt::format(
        "  exact, within the crop (TEST's samples: {} of {}; REF's: {} of {}), at tau [95%]:\n",
        t.exact_test_counted, t.exact_test_samples, t.exact_reference_counted, t.exact_reference_samples);
    out += fmt::format("  {:<14} {:>40}\n", "precision", estimate_text(e.accuracy.within.front()));
    out += fmt::format("  {:<14} {:>40}\n", "recall", estimate_text(e.completeness.within.front()));
    out += fmt::format("  {:<14} {:>40}\n", "F-score", estimate_text(e.f_score_estimate.front()));
  }
  return out;
}

}  // namespace roving
