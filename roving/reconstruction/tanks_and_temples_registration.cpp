#include "roving/reconstruction/tanks_and_temples_registration.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "roving/core/error.h"
#include "roving/reconstruction/correspondence_ransac.h"
#include "roving/reconstruction/spatial_order.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"
#include "roving/reconstruction/voxel_down_sample.h"

namespace roving {
namespace {

constexpr std::size_t kVideoCameras = 1600;     // above this, run.py picks the reference's frames
constexpr double kCameraDistance = 0.2;         // RANSAC's inlier distance (metres, any scene)
constexpr int kCameraSample = 6;                // cameras drawn at a time
constexpr double kUniformPoints = 4e6;          // registration.py's MAX_POINT_NUMBER
const IcpCriteria kToolboxIcp{1e-6, 20, 30};    // ICPConvergenceCriteria(1e-6, max_itr=20), positionally

std::vector<Vec3> centres(const std::vector<Eigen::Matrix4d>& poses) {
  std::vector<Vec3> points;
  points.reserve(poses.size());
  for (const Eigen::Matrix4d& pose : poses) points.emplace_back(pose.block<3, 1>(0, 3));
  return points;
}

}  // namespace

namespace {

// Which points, moved by a transformation, the crop volume holds: a mark per point, and per block
// of kCropBlock points how many are marked before it (the last entry: all of them). The blocks are
// counted on every core, and the points copied after them in order.
constexpr std::size_t kCropBlock = 1 << 14;
struct CropMarks {
  std::vector<std::uint8_t> inside;
  std::vector<std::size_t> before;
};

CropMarks crop_marks(const std::vector<Vec3>& points, const Eigen::Matrix4d& transformation, const CropVolume& crop) {
  const bool identity = transformation == Eigen::Matrix4d::Identity();
  const std::size_t blocks = (points.size() + kCropBlock - 1) / kCropBlock;
  CropMarks marks{std::vector<std::uint8_t>(points.size()), std::vector<std::size_t>(blocks + 1, 0)};
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::size_t count = 0;
    for (std::size_t i = b * kCropBlock; i < std::min(points.size(), (b + 1) * kCropBlock); ++i) {
      marks.inside[i] = crop.contains(identity ? points[i] : transformed_point(transformation, points[i])) ? 1 : 0;
      count += marks.inside[i];
    }
    marks.before[b + 1] = count;
  });
  for (std::size_t b = 0; b < blocks; ++b) marks.before[b + 1] += marks.before[b];
  return marks;
}

// Every `every`-th of the marked points, moved, in order (each moved again: no copy of the cloud).
std::vector<Vec3> moved_marked(const std::vector<Vec3>& points, const Eigen::Matrix4d& transformation,
                               const CropMarks& marks, std::size_t every) {
  const bool identity = transformation == Eigen::Matrix4d::Identity();
  std::vector<Vec3> kept((marks.before.back() + every - 1) / every);
  tbb::parallel_for(std::size_t(0), marks.before.size() - 1, [&](std::size_t b) {
    std::size_t k = marks.before[b];  // the marked points before this block
    for (std::size_t i = b * kCropBlock; i < std::min(points.size(), (b + 1) * kCropBlock); ++i) {
      if (!marks.inside[i]) continue;
      if (k % every == 0) kept[k / every] = identity ? points[i] : transformed_point(transformation, points[i]);
      ++k;
    }
  });
  return kept;
}

// registration.py's crop_and_downsample: the points moved, cropped, and thinned by voxels of
// `voxel_size`, or (0) every k-th point kept with k = round(n / 4 M) where the n cropped points
// are above 4 M. Neither copies the moved cloud whole (30 M points are 720 MB).
std::vector<Vec3> cropped_and_thinned(const std::vector<Vec3>& points, const Eigen::Matrix4d& transformation,
                                      const CropVolume& crop, double voxel_size, const std::string& name) {
  const CropMarks marks = crop_marks(points, transformation, crop);
  if (voxel_size > 0) {
    const bool identity = transformation == Eigen::Matrix4d::Identity();
    return voxel_down_sample(points, voxel_size, name, &marks.inside, identity ? nullptr : &transformation);
  }
  const double n = static_cast<double>(marks.before.back());
  // int(round(n / 4e6)): Python's round, halves to even, as nearbyint rounds by default.
  const auto every = n > kUniformPoints ? static_cast<std::size_t>(std::nearbyint(n / kUniformPoints)) : 1;
  // The same points, in the order of their place in space, as the voxels' means come out: ICP's
  // searches from them then run from cache. Only the order of ICP's sums changes (their last bits).
  std::vector<Vec3> kept = moved_marked(points, transformation, marks, every);
  order_in_space(kept);
  return kept;
}

}  // namespace

std::vector<Vec3> moved_and_cropped(const std::vector<Vec3>& points, const Eigen::Matrix4d& transformation,
                                    const CropVolume& crop) {
  return moved_marked(points, transformation, crop_marks(points, transformation, crop), 1);
}

std::vector<Vec3> matched_camera_centres(const TanksAndTemplesTrajectories& t,
                                         const std::array<std::string, 2>& names) {
  std::vector<Eigen::Matrix4d> poses;
  if (t.reconstruction.size() > kVideoCameras) {
    if (t.mapping.empty()) {
      throw Error(fmt::format("{}: {} cameras, more than {}: run.py then picks the reference's frames by the scene's "
                              "<scene>_mapping_reference.txt; expected it (--tnt-mapping)",
                              names[0], t.reconstruction.size(), kVideoCameras));
    }
    for (const std::size_t frame : t.mapping) {
      if (frame < 1 || frame > t.reconstruction.size()) {
        throw Error(fmt::format("{}: frame {}; expected a frame from 1 to {} (the cameras of {})", names[1], frame,
                                t.reconstruction.size(), names[0]));
      }
      poses.push_back(t.reconstruction[frame - 1]);
    }
  } else {
    poses = t.reconstruction;
  }
  if (poses.size() < t.reference.size() || t.reference.size() < kCameraSample) {
    const bool mapped = t.reconstruction.size() > kVideoCameras;
    throw Error(fmt::format("{}: {} cameras matched to the reference's {}{}; expected at least as many as the "
                            "reference has, and at least {}",
                            mapped ? names[1] : names[0], poses.size(), t.reference.size(),
                            mapped ? fmt::format(" (frames of {})", names[0]) : "", kCameraSample));
  }
  return centres(poses);
}

TanksAndTemplesRegistration tanks_and_temples_registration(const std::vector<Vec3>& reconstruction,
                                                           const std::vector<Vec3>& ground_truth,
                                                           const CropVolume& crop, double tau,
                                                           const TanksAndTemplesTrajectories& trajectories,
                                                           std::uint32_t seed,
                                                           const std::array<std::string, 4>& names,
                                                           const ProgressFn& progress) {
  if (!(std::isfinite(tau) && tau > 0)) {
    throw Error(fmt::format("Tanks and Temples registration: tau {}; expected a length > 0", tau));
  }
  const auto step = [&](std::size_t done) {
    if (progress) progress("registration steps", done, 4);
  };
  step(0);
  TanksAndTemplesRegistration r;
  r.seed = seed;
  const std::vector<Vec3> cameras = matched_camera_centres(trajectories, {names[0], names[1]});
  std::vector<Vec3> reference = centres(trajectories.reference);
  transform_points(trajectories.reference_alignment, reference);
  r.cameras = cameras.size();
  PointPairs pairs(reference.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i] = {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)};
  r.trajectory = ransac_on_pairs(cameras, reference, pairs, kCameraDistance, kCameraSample, {}, seed);
  step(1);
  Eigen::Matrix4d alignment = r.trajectory.transformation;
  const std::array<std::pair<double, double>, 3> rounds = {
      {{tau, tau * 80}, {tau / 2.0, tau * 20}, {0.0, 2 * tau}}};  // (voxel size, largest pair distance)
  for (std::size_t k = 0; k < rounds.size(); ++k) {
    TanksAndTemplesRegistration::Round& round = r.rounds[k];
    round.voxel_size = rounds[k].first;
    round.max_distance = rounds[k].second;
    const std::vector<Vec3> target =
        cropped_and_thinned(ground_truth, Eigen::Matrix4d::Identity(), crop, round.voxel_size, names[3]);
    // nanoflann builds a tree on one core: the target's while the source is moved and thinned.
    std::unique_ptr<PointTree> tree;
    std::vector<Vec3> source;
    tbb::parallel_invoke(
        [&] { tree = std::make_unique<PointTree>(target); },
        [&] { source = cropped_and_thinned(reconstruction, alignment, crop, round.voxel_size, names[2]); });
    round.source_points = source.size();
    round.target_points = target.size();
    if (source.empty() || target.empty()) {
      throw Error(fmt::format("Tanks and Temples registration, round {}: {} of {}'s points and {} of {}'s in the crop "
                              "volume; expected some of each (is the trajectory the reconstruction's?)",
                              k + 1, source.size(), names[2], target.size(), names[3]));
    }
    round.icp = icp_point_to_point(std::move(source), *tree, round.max_distance, kToolboxIcp);
    round.icp.pairs.clear();
    alignment = round.icp.transformation * alignment;  // np.matmul(reg.transformation, init_trans)
    round.transformation = alignment;
    step(k + 2);
  }
  r.transformation = alignment;
  return r;
}

}  // namespace roving
