// --protocol: a benchmark's own evaluation on the pair, step by step (DTU's, as DTUeval-python
// computes it: roving/reconstruction/dtu_protocol.h; Tanks and Temples', as its toolbox computes
// it: roving/reconstruction/tanks_and_temples_protocol.h), from the data set's own files.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "roving/reconstruction/dtu_protocol.h"
#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"
#include "roving/reconstruction/tanks_and_temples_registration.h"
#include "roving/representations/model.h"

namespace roving {

struct DtuPlan {
  DtuOptions options;
  std::string obs_mask, plane;  // ObsMask<scan>_10.mat, Plane<scan>.mat
};

struct DtuReport {
  DtuFigures figures;
  std::string obs_mask, plane;
  double seconds = 0;
  // With --symmetric, the exact figures where the protocol measures: accuracy over TEST's samples
  // within the box and observed, completeness over REF's above the plane, every distance counted;
  // the same with the protocol's cap (the distances below max_dist only); how many samples each
  // direction counted (below the cap: the figures' hits), of how many.
  std::optional<ReconstructionFigures> exact, exact_below_cap;
  std::size_t exact_test_counted = 0, exact_test_samples = 0, exact_reference_counted = 0, exact_reference_samples = 0;
};

// The data set's files for one scan: its observation mask and ground plane.
struct DtuFiles {
  DtuObservationMask mask;
  std::array<double, 4> plane{};
};

// Reads them, before the models (a wrong file fails at once). Throws roving::Error naming the file
// and variable that is missing or malformed.
DtuFiles read_dtu_files(const DtuPlan& plan);

// The protocol with `ground_truth` (REF: DTU's STL points, or a mesh's vertices) and
// `reconstruction` (TEST: a mesh, sampled as the script samples it, or a point cloud). Throws
// roving::Error naming a model that is neither a mesh nor a point cloud. `progress` hears the runs'
// steps.
DtuReport dtu_report(const Model& ground_truth, const Model& reconstruction, const DtuPlan& plan,
                     const DtuFiles& files, const ProgressFn& progress = {});

// Sets report.exact (every distance) and report.exact_below_cap (those below max_dist) from the two
// directions' correspondences (REF's samples measured against TEST, TEST's against REF), as
// reconstruction_figures takes them, restricted to the protocol's region, and the samples counted.
void set_exact_within_region(DtuReport& report, const DtuPlan& plan, const DtuFiles& files,
                             const CorrespondenceSet& reference_to_test, const CorrespondenceSet& test_to_reference,
                             const std::vector<double>& thresholds, bool area_uniform);

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
};

struct TanksAndTemplesReport {
  TanksAndTemplesFigures figures;
  std::string scene, crop, alignment, curves_png, plys;
  std::optional<TanksAndTemplesClouds> clouds;  // with --tnt-plys: what they show
  Eigen::Matrix4d alignment_matrix = Eigen::Matrix4d::Identity();
  std::string trajectory, reference_trajectory, mapping;
  // run.py's registration, one run per seed; the first gave alignment_matrix and the figures.
  std::vector<TanksAndTemplesRegistrationRun> registrations;
  double seconds = 0, registration_seconds = 0;
  // With --symmetric, the exact figures within the crop volume: precision's side over TEST's
  // (aligned) samples inside it, recall's over REF's; how many samples each direction counted.
  std::optional<ReconstructionFigures> exact;
  std::size_t exact_test_counted = 0, exact_test_samples = 0, exact_reference_counted = 0, exact_reference_samples = 0;
};

// Reads the crop volume, the alignment (a 4 x 4 matrix as np.loadtxt reads run.py's
// <scene>_trans.txt: four rows of four numbers; its last row 0 0 0 1) and the trajectories, before
// the models. Throws roving::Error naming the file and what was expected.
TanksAndTemplesFiles read_tanks_and_temples_files(const TanksAndTemplesPlan& plan);

// run.py's registration of TEST (the reconstruction, in its own frame) to REF, once per seed: the
// first run's transformation replaces files.alignment. The runs after the first are scored here
// (on points moved by their own transformation), the first by tanks_and_temples_report.
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
                                               const TanksAndTemplesPlan& plan, const TanksAndTemplesFiles& files,
                                               const ProgressFn& progress = {});

// Sets report.exact from the two directions' correspondences, each restricted to the crop volume,
// at tau and then at each of `thresholds`.
void set_exact_within_crop(TanksAndTemplesReport& report, const TanksAndTemplesFiles& files,
                           const CorrespondenceSet& reference_to_test, const CorrespondenceSet& test_to_reference,
                           const std::vector<double>& thresholds, bool area_uniform);

}  // namespace roving
