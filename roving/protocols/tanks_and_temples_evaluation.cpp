// Tanks and Temples' evaluation on a pair (tanks_and_temples_evaluation.h): its files read and
// checked, run.py's registration, the protocol run, its exact figures within the crop.
#include "roving/protocols/tanks_and_temples_evaluation.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/reconstruction/trajectory_log.h"

namespace roving {

namespace {

// config.py's scenes_tau_dict (the training scenes; the others are scored by the benchmark's server).
constexpr std::pair<const char*, double> kSceneTau[] = {
    {"Barn", 0.01},      {"Caterpillar", 0.005}, {"Church", 0.025}, {"Courthouse", 0.025},
    {"Ignatius", 0.003}, {"Meetingroom", 0.01},  {"Truck", 0.005},
};

// np.loadtxt's reading of a 4 x 4 matrix: four lines of four numbers ('#' starts a comment).
Eigen::Matrix4d read_alignment(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot read the alignment", path));
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    std::vector<double> row;
    std::size_t at = 0;
    while (true) {
      at = line.find_first_not_of(" \t\r,", at);
      if (at == std::string::npos) break;
      const std::size_t end = std::min(line.find_first_of(" \t\r,", at), line.size());
      double value = 0;
      const auto [last, error] = std::from_chars(line.data() + at, line.data() + end, value);
      if (error != std::errc() || last != line.data() + end || !std::isfinite(value)) {
        throw Error(fmt::format("{}: line {} holds '{}'; expected a 4 x 4 matrix of finite numbers", path,
                                rows.size() + 1, line.substr(at, end - at)));
      }
      row.push_back(value);
      at = end;
    }
    if (row.empty()) continue;
    if (row.size() != 4 || rows.size() == 4) {
      throw Error(
          fmt::format("{}: a row of {} numbers after {} rows; expected a 4 x 4 matrix, four rows of four",
                      path, row.size(), rows.size()));
    }
    rows.push_back(std::move(row));
  }
  if (rows.size() != 4)
    throw Error(fmt::format("{}: {} rows; expected a 4 x 4 matrix, four rows of four", path, rows.size()));
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = rows[r][c];
  }
  if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1) || !(std::abs(m.topLeftCorner<3, 3>().determinant()) > 0)) {
    throw Error(fmt::format(
        "{}: expected an invertible affine transform (its last row 0 0 0 1); found last row {} {} {} {}",
        path, m(3, 0), m(3, 1), m(3, 2), m(3, 3)));
  }
  return m;
}

// A model's points as Open3D's read_point_cloud reads its file: a cloud's points, a mesh's vertices.
const std::vector<Vec3>& protocol_points(const Model& model, const char* role, std::vector<Vec3>& storage) {
  if (model.type == ModelType::Points) return model.points.positions;
  if (model.type != ModelType::Mesh) {
    throw Error(
        fmt::format("{}: --protocol tanks-and-temples takes a mesh or a point cloud as {}; found a {} model",
                    model.path(), role, to_string(model.type)));
  }
  storage = model.mesh.mesh.positions().to_vector();
  return storage;
}

}  // namespace

std::optional<double> tanks_and_temples_tau(const std::string& scene) {
  for (const auto& [name, tau] : kSceneTau) {
    if (scene == name) return tau;
  }
  return std::nullopt;
}

std::string tanks_and_temples_scenes() {
  std::string names;
  for (const auto& entry : kSceneTau) names += (names.empty() ? "" : ", ") + std::string(entry.first);
  return names;
}

TanksAndTemplesFiles read_tanks_and_temples_files(const TanksAndTemplesPlan& plan) {
  TanksAndTemplesFiles files;
  files.crop = read_crop_volume(plan.crop);
  if (!plan.alignment.empty()) files.alignment = read_alignment(plan.alignment);
  if (!plan.trajectory.empty()) {
    TanksAndTemplesTrajectories& t = files.trajectories.emplace();
    t.reconstruction = read_trajectory_log(plan.trajectory);
    t.reference = read_trajectory_log(plan.reference_trajectory);
    if (!plan.mapping.empty()) t.mapping = read_frame_mapping(plan.mapping);
    t.reference_alignment = files.alignment;
    // The cameras' match is checked now, before the models load.
    matched_camera_centres(t, {plan.trajectory, plan.mapping.empty() ? "the mapping" : plan.mapping});
  }
  return files;
}

std::vector<TanksAndTemplesRegistrationRun> register_tanks_and_temples(const Model& ground_truth,
                                                                       const Model& reconstruction,
                                                                       const TanksAndTemplesPlan& plan,
                                                                       TanksAndTemplesFiles& files,
                                                                       const ProgressFn& progress) {
  std::vector<Vec3> truth_storage, reconstruction_storage;
  const std::vector<Vec3>& truth = protocol_points(ground_truth, "REF (the ground truth)", truth_storage);
  const std::vector<Vec3>& points =
      protocol_points(reconstruction, "TEST (the reconstruction)", reconstruction_storage);
  std::vector<TanksAndTemplesRegistrationRun> runs(static_cast<std::size_t>(plan.runs));
  for (std::size_t k = 0; k < runs.size(); ++k) {
    TanksAndTemplesRegistrationRun& run = runs[k];
    // Each run's steps, counted over all of them.
    const auto steps = [&](const char* what, std::size_t done, std::size_t total) {
      if (progress) progress(what, k * total + done, runs.size() * total);
    };
    run.registration = tanks_and_temples_registration(
        points, truth, *files.crop, plan.options.tau, *files.trajectories,
        plan.first_seed + static_cast<std::uint32_t>(k),
        {plan.trajectory, plan.mapping, reconstruction.path(), ground_truth.path()}, steps);
    // The points the crop keeps give the same figures as all of them (the crop runs first).
    const TanksAndTemplesFigures f = tanks_and_temples_figures(
        moved_and_cropped(points, run.registration.transformation, *files.crop), truth, *files.crop,
        plan.options, {}, {reconstruction.path(), ground_truth.path()});
    run.precision = f.precision;
    run.recall = f.recall;
    run.fscore = f.fscore;
  }
  TanksAndTemplesRegistrationRun& reported = runs[modal_run(runs)];
  reported.reported = true;
  files.alignment = reported.registration.transformation;
  return runs;
}

std::size_t modal_run(const std::vector<TanksAndTemplesRegistrationRun>& runs) {
  const auto same = [](const TanksAndTemplesRegistrationRun& a, const TanksAndTemplesRegistrationRun& b) {
    return a.precision == b.precision && a.recall == b.recall && a.fscore == b.fscore;
  };
  std::size_t best = 0, best_count = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto count = static_cast<std::size_t>(
        std::count_if(runs.begin(), runs.end(), [&](const auto& run) { return same(run, runs[i]); }));
    if (count > best_count) best = i, best_count = count;
  }
  return best;
}

const TanksAndTemplesRegistrationRun& reported_run(const std::vector<TanksAndTemplesRegistrationRun>& runs) {
  const auto found = std::find_if(runs.begin(), runs.end(), [](const auto& run) { return run.reported; });
  return found != runs.end() ? *found : runs.front();
}

void align_test_model(Model& test, const Eigen::Matrix4d& alignment) {
  if (alignment == Eigen::Matrix4d::Identity()) return;
  if (test.type == ModelType::Points) {
    transform_points(alignment, test.points.positions);
    const Eigen::Matrix3d normal_map = alignment.topLeftCorner<3, 3>().inverse().transpose();
    for (Vec3& n : test.points.normals) n = (normal_map * n).normalized();
  } else if (test.type == ModelType::Mesh) {
    const TriangleMesh& mesh = test.mesh.mesh;
    std::vector<Vec3> positions = mesh.positions().to_vector();
    transform_points(alignment, positions);
    std::vector<Colour> colours = mesh.vertex_colours();
    TriangleMesh moved(std::move(positions), mesh.triangles().to_vector(), test.path());
    if (!colours.empty()) moved.set_vertex_colours(std::move(colours), test.path());
    test.mesh.mesh = std::move(moved);
  } else {
    throw Error(fmt::format("{}: --tnt-alignment moves a mesh or a point cloud; found a {} model",
                            test.path(), to_string(test.type)));
  }
}

TanksAndTemplesReport tanks_and_temples_report(const Model& ground_truth, const Model& reconstruction,
                                               const TanksAndTemplesPlan& plan,
                                               const TanksAndTemplesFiles& files,
                                               const ProgressFn& progress) {
  const Stopwatch watch;
  TanksAndTemplesReport report;
  report.scene = plan.scene;
  report.crop = plan.crop;
  report.alignment = plan.alignment;
  report.curves_png = plan.curves_png;
  report.plys = plan.plys;
  if (!plan.plys.empty()) report.clouds.emplace();
  report.alignment_matrix = files.alignment;
  report.trajectory = plan.trajectory;
  report.reference_trajectory = plan.reference_trajectory;
  report.mapping = plan.mapping;
  std::vector<Vec3> truth_storage, reconstruction_storage;
  const std::vector<Vec3>& truth = protocol_points(ground_truth, "REF (the ground truth)", truth_storage);
  const std::vector<Vec3>& points =
      protocol_points(reconstruction, "TEST (the reconstruction)", reconstruction_storage);
  report.figures = tanks_and_temples_figures(points, truth, *files.crop, plan.options, progress,
                                             {reconstruction.path(), ground_truth.path()},
                                             report.clouds ? &*report.clouds : nullptr);
  report.seconds = watch.seconds();
  return report;
}

void set_exact_within_crop(TanksAndTemplesReport& report, const TanksAndTemplesFiles& files,
                           const CorrespondenceSet& reference_to_test,
                           const CorrespondenceSet& test_to_reference, const std::vector<double>& thresholds,
                           bool area_uniform) {
  const auto inside = [&](const SampleSet& samples, std::size_t& counted, std::size_t& total) {
    std::vector<std::uint8_t> marks(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k)
      marks[k] = files.crop->contains(samples.positions[k]) ? 1 : 0;
    counted = static_cast<std::size_t>(std::count(marks.begin(), marks.end(), 1));
    total = samples.size();
    return marks;
  };
  const std::vector<std::uint8_t> reference_inside =
      inside(*reference_to_test.samples, report.exact_reference_counted, report.exact_reference_samples);
  const std::vector<std::uint8_t> test_inside =
      inside(*test_to_reference.samples, report.exact_test_counted, report.exact_test_samples);
  CorrespondenceSet recall = reference_to_test, precision = test_to_reference;
  recall.region = &reference_inside;
  precision.region = &test_inside;
  // tau first (the protocol's threshold, in exact form), then --threshold's others.
  std::vector<double> taus{report.figures.options.tau};
  for (const double t : thresholds) {
    if (t != taus.front()) taus.push_back(t);
  }
  report.exact = reconstruction_figures(recall, precision, taus, area_uniform);
}

}  // namespace roving
