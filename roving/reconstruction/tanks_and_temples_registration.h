// Tanks and Temples' run.py before it scores (registration.py of its toolbox): it aligns the
// reconstruction's camera trajectory to the scene's reference (COLMAP's cameras moved by the
// scene's <scene>_trans.txt) by RANSAC on their centres, then refines that alignment by three
// rounds of point-to-point ICP with scale on both clouds cropped to the scene's volume:
//   1. voxel down-sampled at tau, pairs closer than 80 tau;
//   2. voxel down-sampled at tau / 2, pairs closer than 20 tau;
//   3. uniformly down-sampled to about 4 M points where a cloud has more, pairs closer than 2 tau.
// Each round's ICP is called as the toolbox calls it: ICPConvergenceCriteria(1e-6, 20) sets the
// relative fitness to 1e-6 and the relative RMSE to 20 (not the iterations, which stay Open3D's
// 30), so a round stops as soon as its count of pairs is unchanged.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/reconstruction/crop_volume.h"
#include "roving/reconstruction/point_registration.h"

namespace roving {

struct TanksAndTemplesTrajectories {
  std::vector<Eigen::Matrix4d> reconstruction;  // the reconstruction's camera poses (its .log)
  std::vector<Eigen::Matrix4d> reference;       // the scene's COLMAP cameras (<scene>_COLMAP_SfM.log)
  // <scene>_mapping_reference.txt: for each reference camera, its frame in a video trajectory
  // (1-based). run.py reads it where the reconstruction's trajectory has more than 1,600 cameras.
  std::vector<std::size_t> mapping;
  Eigen::Matrix4d reference_alignment = Eigen::Matrix4d::Identity();  // <scene>_trans.txt
};

struct TanksAndTemplesRegistration {
  std::uint32_t seed = 0;
  std::size_t cameras = 0;            // the reconstruction's cameras matched, one per reference camera
  PointRegistration trajectory;       // RANSAC's alignment of the camera centres
  struct Round {
    double voxel_size = 0;            // 0: uniform (every k-th point, k = 1 under 4 M points)
    double max_distance = 0;
    std::size_t source_points = 0, target_points = 0;  // after cropping and down-sampling
    PointRegistration icp;            // its transformation: this round's refinement alone
    Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();  // the alignment after it
  };
  std::array<Round, 3> rounds;
  Eigen::Matrix4d transformation = Eigen::Matrix4d::Identity();  // what EvaluateHisto is given
};

// registration.py's crop_and_downsample, first half: the points moved by `transformation` (as
// transform_points moves them), those inside the crop volume kept, in order. Each is moved twice
// rather than the cloud copied whole (30 M points are 720 MB).
std::vector<Vec3> moved_and_cropped(const std::vector<Vec3>& points, const Eigen::Matrix4d& transformation,
                                    const CropVolume& crop);

// The cameras of a trajectory run.py matches to the reference's, as centres: all of them, or where
// there are more than 1,600, those `mapping` names. Throws roving::Error (naming `names`: the
// trajectory's file, the mapping's) for fewer cameras than the reference has, an empty mapping
// where it is needed, or a frame outside the trajectory.
std::vector<Vec3> matched_camera_centres(const TanksAndTemplesTrajectories& trajectories,
                                         const std::array<std::string, 2>& names);

// run.py's registration of `reconstruction` (in its own frame) to `ground_truth`, RANSAC's draws
// from `seed`. `names` name in messages the trajectory's file, the mapping's, the reconstruction's
// and the ground truth's. `progress` hears its steps ("registration steps"). Throws roving::Error
// as matched_camera_centres does, and where a round finds no point of a cloud in the crop volume.
TanksAndTemplesRegistration tanks_and_temples_registration(const std::vector<Vec3>& reconstruction,
                                                           const std::vector<Vec3>& ground_truth,
                                                           const CropVolume& crop, double tau,
                                                           const TanksAndTemplesTrajectories& trajectories,
                                                           std::uint32_t seed,
                                                           const std::array<std::string, 4>& names,
                                                           const ProgressFn& progress = {});

}  // namespace roving
