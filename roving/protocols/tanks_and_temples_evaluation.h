// Tanks and Temples' evaluation (`--protocol tanks-and-temples`) on a pair, as its toolbox computes
// it (roving/reconstruction/tanks_and_temples_protocol.h), from the scene's own files: crop volume,
// alignment, and for run.py's registration the trajectories; and the report's section of it
// (docs/report-json.md's `tanks_and_temples_protocol`).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"
#include "roving/reconstruction/tanks_and_temples_registration.h"
#include "roving/representations/model.h"

namespace roving {

struct TanksAndTemplesPlan {
  TanksAndTemplesOptions options;
  std::string scene;            // where tau is the scene's (--tnt-scene), its name
  std::string crop, alignment;  // <scene>.json; the 4 x 4 alignment (none: the identity)
  std::string curves_png;       // --tnt-curves: the precision and recall curves as PNG
  std::string plys;             // --tnt-plys: the viewing files' prefix (PREFIX.precision.ply, .recall.ply)
  // run.py's registration, where a trajectory is given: the reconstruction's cameras (.log), the
  // scene's (<scene>_COLMAP_SfM.log), its frame mapping (may be empty), RANSAC's seeds and runs.
  std::string trajectory, reference_trajectory, mapping;
  std::uint32_t first_seed = 1;
  int runs = 1;
};

// The scenes' tau, as the toolbox's config.py sets them (metres); nullopt for another name.
std::optional<double> tanks_and_temples_tau(const std::string& scene);
// Their names, for messages.
std::string tanks_and_temples_scenes();

struct TanksAndTemplesFiles {
  std::optional<CropVolume> crop;
  Eigen::Matrix4d alignment = Eigen::Matrix4d::Identity();
  std::optional<TanksAndTemplesTrajectories> trajectories;  // with a trajectory (alignment: the scene's)
};

// One registration and the protocol's figures after it.
struct TanksAndTemplesRegistrationRun {
  TanksAndTemplesRegistration registration;
  double precision = 0, recall = 0, fscore = 0;
  bool reported = false;  // its alignment gave the report's figures
};

// The run whose figures the most runs give, the earliest of them where several tie (the first of
// all where every run differs): run.py draws RANSAC's pairs unseeded, and where it gives one result
// nearly every time, most seeds give that result too, where one seed alone may not.
std::size_t modal_run(const std::vector<TanksAndTemplesRegistrationRun>& runs);

// The run marked reported (the first where none is).
const TanksAndTemplesRegistrationRun& reported_run(const std::vector<TanksAndTemplesRegistrationRun>& runs);

struct TanksAndTemplesReport {
  TanksAndTemplesFigures figures;
  std::string scene, crop, alignment, curves_png, plys;
  std::optional<TanksAndTemplesClouds> clouds;  // with --tnt-plys: what they show
  Eigen::Matrix4d alignment_matrix = Eigen::Matrix4d::Identity();
  std::string trajectory, reference_trajectory, mapping;
  // run.py's registration, one run per seed; the one marked reported gave alignment_matrix and the figures.
  std::vector<TanksAndTemplesRegistrationRun> registrations;
  double seconds = 0, registration_seconds = 0;
  // With --symmetric, the exact figures within the crop volume: precision's side over TEST's
  // (aligned) samples inside it, recall's over REF's; how many samples each direction counted.
  std::optional<ReconstructionFigures> exact;
  std::size_t exact_test_counted = 0, exact_test_samples = 0, exact_reference_counted = 0,
              exact_reference_samples = 0;
};

// Reads the crop volume, the alignment (a 4 x 4 matrix as np.loadtxt reads run.py's
// <scene>_trans.txt: four rows of four numbers; its last row 0 0 0 1) and the trajectories, before
// the models. Throws roving::Error naming the file and what was expected.
TanksAndTemplesFiles read_tanks_and_temples_files(const TanksAndTemplesPlan& plan);

// run.py's registration of TEST (the reconstruction, in its own frame) to REF, once per seed, each
// run scored here (on points moved by its own transformation). The modal run (modal_run) is marked
// reported and its transformation replaces files.alignment; tanks_and_temples_report scores it again
// with everything else the report gives.
std::vector<TanksAndTemplesRegistrationRun> register_tanks_and_temples(const Model& ground_truth,
                                                                       const Model& reconstruction,
                                                                       const TanksAndTemplesPlan& plan,
                                                                       TanksAndTemplesFiles& files,
                                                                       const ProgressFn& progress = {});

// TEST moved by the alignment, as the toolbox moves the reconstruction (Open3D's transform on its
// points; a mesh keeps its faces, a cloud's normals turn with it). The identity leaves it as it is.
void align_test_model(Model& test, const Eigen::Matrix4d& alignment);

// The protocol with `ground_truth` (REF: a point cloud, or a mesh's vertices) and `reconstruction`
// (TEST, aligned: a point cloud, or a mesh's vertices, as Open3D's read_point_cloud reads it).
TanksAndTemplesReport tanks_and_temples_report(const Model& ground_truth, const Model& reconstruction,
                                               const TanksAndTemplesPlan& plan,
                                               const TanksAndTemplesFiles& files,
                                               const ProgressFn& progress = {});

// Sets report.exact from the two directions' correspondences, each restricted to the crop volume,
// at tau and then at each of `thresholds`.
void set_exact_within_crop(TanksAndTemplesReport& report, const TanksAndTemplesFiles& files,
                           const CorrespondenceSet& reference_to_test,
                           const CorrespondenceSet& test_to_reference, const std::vector<double>& thresholds,
                           bool area_uniform);

nlohmann::json tnt_json(const TanksAndTemplesReport& report);
// The text section: the registration's rounds, the protocol's figures (and their spread over the
// registrations' seeds), the files written, the exact figures within the crop.
std::string tnt_lines(const TanksAndTemplesReport& report);

}  // namespace roving
