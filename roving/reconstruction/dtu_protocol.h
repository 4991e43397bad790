// The DTU MVS benchmark's evaluation as DTUeval-python (github.com/jzhangbs/DTUeval-python, eval.py
// at 45b4fec) computes it, the faster stand-in for DTU's MATLAB code that reconstruction papers
// report: the reconstruction sampled (a mesh) or taken as points, shuffled, thinned to one point per
// `density`, kept within the observation mask; accuracy is its mean distance to the structured-
// light ground truth, completeness the ground truth's (above the ground plane) to the thinned
// reconstruction, each mean over the distances below `max_dist`; overall is their mean.
// Every step follows the script, its single-precision box included; its one unseeded line, the
// shuffle before thinning, is ours seeded (or left out: the points' own order, the reference that
// the script with that line removed reproduces to the last digits).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// ObsMask{scan}_10.mat: the voxels the scanner observed, and their grid.
struct DtuObservationMask {
  std::array<std::size_t, 3> dims{};
  std::vector<std::uint8_t> observed;  // dims[0] * dims[1] * dims[2], the first index fastest (MATLAB's order)
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  // BB's two rows
  double resolution = 0;                                 // Res: a voxel's side
};

struct DtuOptions {
  double density = 0.2;   // --downsample_density: the sampling step and the thinning radius
  double patch = 60;      // --patch_size: the margin of the box
  double max_dist = 20;   // --max_dist: distances at or beyond it are left out of the means
  // The shuffle before thinning: seeds first_seed, first_seed + 1, ... one per run; none: one
  // run in the points' own order (vertices, then the samples face by face).
  std::optional<std::uint64_t> first_seed = 1;
  int runs = 5;
};

struct DtuRun {
  std::optional<std::uint64_t> seed;
  double accuracy = 0, completeness = 0, overall = 0;  // NaN where no distance is below max_dist
  std::size_t thinned = 0;       // points after thinning (data_down)
  std::size_t in_box = 0;        // of them within the box and its margin (data_in)
  std::size_t observed = 0;      // of those within the mask (data_in_obs): accuracy's points
  std::size_t accuracy_counted = 0, completeness_counted = 0;  // distances below max_dist
};

struct DtuFigures {
  DtuOptions options;
  std::size_t reconstruction_points = 0;  // before thinning: the vertices and the samples
  std::size_t samples = 0;                // of them sampled from the faces (0 for points)
  std::size_t ground_truth_points = 0, ground_truth_above = 0;  // above the ground plane: completeness's points
  std::vector<DtuRun> runs;  // the first is the one reported
};

// Where the protocol measures: accuracy counts the reconstruction's points within the mask's box
// (in single precision, with `patch` below and twice it above, as the script pads it) whose voxel
// was observed; completeness counts the ground truth's points above the plane. Throws
// roving::Error for a patch that is not finite and >= 0, or a mask whose size is not its dims'.
class DtuRegion {
 public:
  DtuRegion(const DtuObservationMask& mask, const std::array<double, 4>& plane, double patch);
  bool in_box(const Vec3& p) const;
  bool observed(const Vec3& p) const;  // within the box, and its voxel observed
  bool above(const Vec3& p) const;     // P . (x, y, z, 1) > 0

 private:
  const DtuObservationMask& mask_;
  std::array<double, 4> plane_;
  std::array<double, 3> low_{}, high_{}, origin_{};
};

// DTUeval-python's points of a mesh: its vertices, then per face of non-zero area the points of a
// grid of step `density` (scaled to the face's shape) strictly inside it. Throws roving::Error
// naming `name` when they would number over 10^9 (a model in other units than the density's).
std::vector<Vec3> dtu_mesh_points(const TriangleMesh& mesh, const std::string& name, double density,
                                  std::size_t* samples = nullptr);

// The protocol on `reconstruction` (its points, as dtu_mesh_points gives them or as read) against
// `ground_truth`, with the mask and the ground plane `plane` (P . (x, y, z, 1) > 0 is kept).
// `progress`, where given, hears each run's steps as done of total ("protocol runs"); what it
// throws stops the protocol. Throws roving::Error for options that are not finite and > 0, or a
// mask whose size is not its dims'.
DtuFigures dtu_figures(const std::vector<Vec3>& reconstruction, const std::vector<Vec3>& ground_truth,
                       const DtuObservationMask& mask, const std::array<double, 4>& plane, const DtuOptions& options,
                       const ProgressFn& progress = {});

}  // namespace roving
