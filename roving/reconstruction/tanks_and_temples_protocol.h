// The Tanks and Temples benchmark's evaluation as its toolbox computes it (github.com/isl-org/
// TanksAndTemples, python_toolbox/evaluation: EvaluateHisto in evaluation.py, called by run.py):
// the reconstruction, aligned to the ground truth, and the ground truth are each cropped to the
// scene's volume and voxel down-sampled at tau / 2; precision is the share of the reconstruction's
// points whose nearest ground-truth point is closer than tau, recall the share of the ground
// truth's points closer than tau to the reconstruction, F = 2 P R / (P + R); the curves are the
// cumulative shares of each direction's distances over [0, 5 tau) in steps of tau / 100.
// Every step is Open3D 0.16's (its transform, crop, down-sampling and nearest-point distances,
// to the last bit) and NumPy's (the histogram's edges and counts). No step is random.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/triangle_mesh.h"
#include "roving/reconstruction/crop_volume.h"

namespace roving {

struct TanksAndTemplesOptions {
  double tau = 0;           // the scene's threshold (config.py's scenes_tau_dict), the models' units (metres)
  double voxel_size = 0;    // run.py passes tau / 2
  double plot_stretch = 5;  // the curves run over [0, tau * plot_stretch)
};

struct TanksAndTemplesFigures {
  TanksAndTemplesOptions options;
  std::size_t reconstruction_points = 0, reconstruction_cropped = 0, reconstruction_thinned = 0;
  std::size_t ground_truth_points = 0, ground_truth_cropped = 0, ground_truth_thinned = 0;
  std::size_t precision_counted = 0, recall_counted = 0;  // distances below tau
  // 0 where either cloud is empty after cropping (as the script sets them); F is 0 where P + R is.
  double precision = 0, recall = 0, fscore = 0;
  // np.arange(0, tau * plot_stretch, tau / 100), and after each edge but the first the share of
  // each direction's distances below it (at or below, for the last: np.histogram's closed last bin).
  std::vector<double> edges, cumulative_precision, cumulative_recall;
};

// What the toolbox writes for viewing (evaluation.py's <scene>.precision.ply and .recall.ply): each
// cloud cropped and thinned, and each point's distance to the other (precision's side, then recall's).
struct TanksAndTemplesClouds {
  std::vector<Vec3> reconstruction, ground_truth;
  std::vector<double> precision_distances, recall_distances;
};

// Open3D's PointCloud::transform: each point (x, y, z, 1) times the 4 x 4 matrix, divided by the
// result's w, the products summed in Eigen's order (the columns scaled and added left to right).
// Inline: every round of the registration moves every point of the cloud.
inline Vec3 transformed_point(const Eigen::Matrix4d& m, const Vec3& p) {
  double r[4];
  for (int row = 0; row < 4; ++row) r[row] = ((m(row, 0) * p[0] + m(row, 1) * p[1]) + m(row, 2) * p[2]) + m(row, 3);
  if (r[3] == 1.0) return Vec3(r[0], r[1], r[2]);  // x / 1 is x, bit for bit: three divisions saved
  return Vec3(r[0] / r[3], r[1] / r[3], r[2] / r[3]);
}
void transform_points(const Eigen::Matrix4d& transformation, std::vector<Vec3>& points);

// The curves' edges, as np.arange(0, stop, step) makes them: ceil(stop / step) values k * step.
std::vector<double> histogram_edges(double stop, double step);

// After each edge but the first, the share of `distances` below it (at or below, for the last).
std::vector<double> cumulative_shares(std::vector<double> distances, const std::vector<double>& edges);

// The protocol on `reconstruction` (already aligned: transform_points) against `ground_truth`,
// both as points, named in messages by `names` (the reconstruction's, the ground truth's).
// `progress` hears its steps ("protocol steps"); `clouds`, where given, receives the thinned clouds
// and their distances. Throws roving::Error for a tau or a voxel size
// that is not finite and > 0, one too small for a cloud's extent, or a plot_stretch not >= 1.
TanksAndTemplesFigures tanks_and_temples_figures(const std::vector<Vec3>& reconstruction,
                                                 const std::vector<Vec3>& ground_truth, const CropVolume& crop,
                                                 const TanksAndTemplesOptions& options, const ProgressFn& progress = {},
                                                 const std::array<std::string, 2>& names = {"reconstruction",
                                                                                            "ground truth"},
                                                 TanksAndTemplesClouds* clouds = nullptr);

}  // namespace roving
