#include "roving/reconstruction/tanks_and_temples_protocol.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "roving/core/error.h"
#include "roving/reconstruction/point_tree.h"
#include "roving/reconstruction/voxel_down_sample.h"

namespace roving {

void transform_points(const Eigen::Matrix4d& m, std::vector<Vec3>& points) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1 << 14), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) points[i] = transformed_point(m, points[i]);
  });
}

std::vector<double> histogram_edges(double stop, double step) {
  const double count = std::ceil(stop / step);
  std::vector<double> edges(count > 0 ? static_cast<std::size_t>(count) : 0);
  for (std::size_t k = 0; k < edges.size(); ++k) edges[k] = static_cast<double>(k) * step;
  return edges;
}

std::vector<double> cumulative_shares(std::vector<double> distances, const std::vector<double>& edges) {
  if (edges.size() < 2 || distances.empty()) return {};
  tbb::parallel_sort(distances.begin(), distances.end());
  std::vector<double> shares(edges.size() - 1);
  const double total = static_cast<double>(distances.size());
  for (std::size_t i = 1; i < edges.size(); ++i) {
    const auto end = i + 1 < edges.size() ? std::lower_bound(distances.begin(), distances.end(), edges[i])
                                          : std::upper_bound(distances.begin(), distances.end(), edges[i]);
    // np.histogram counts from the first edge, 0: distances are never below it.
    shares[i - 1] = static_cast<double>(end - distances.begin()) / total;
  }
  return shares;
}

namespace {

// Which points are inside the crop volume.
std::vector<std::uint8_t> inside_crop(const std::vector<Vec3>& points, const CropVolume& crop) {
  std::vector<std::uint8_t> inside(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1 << 14), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) inside[i] = crop.contains(points[i]) ? 1 : 0;
  });
  return inside;
}

std::size_t count_below(const std::vector<double>& distances, double tau) {
  return static_cast<std::size_t>(std::count_if(distances.begin(), distances.end(), [&](double d) { return d < tau; }));
}

}  // namespace

TanksAndTemplesFigures tanks_and_temples_figures(const std::vector<Vec3>& reconstruction,
                                                 const std::vector<Vec3>& ground_truth, const CropVolume& crop,
                                                 const TanksAndTemplesOptions& options, const ProgressFn& progress,
                                                 const std::array<std::string, 2>& names,
                                                 TanksAndTemplesClouds* clouds) {
  for (const auto& [name, value] : {std::pair{"tau", options.tau}, {"voxel size", options.voxel_size}}) {
    if (!(std::isfinite(value) && value > 0)) {
      throw Error(fmt::format("Tanks and Temples protocol: {} {}; expected a length > 0", name, value));
    }
  }
  if (!(std::isfinite(options.plot_stretch) && options.plot_stretch >= 1)) {
    throw Error(fmt::format("Tanks and Temples protocol: plot stretch {}; expected a number >= 1", options.plot_stretch));
  }
  TanksAndTemplesFigures f;
  f.options = options;
  f.reconstruction_points = reconstruction.size();
  f.ground_truth_points = ground_truth.size();
  constexpr std::size_t kSteps = 3;
  const auto step = [&](std::size_t done) {
    if (progress) progress("protocol steps", done, kSteps);
  };
  step(0);
  // Each cloud cropped (a mark per point, not a copy) and down-sampled.
  const auto thinned = [&](const std::vector<Vec3>& points, const std::string& name, std::size_t& cropped) {
    const std::vector<std::uint8_t> inside = inside_crop(points, crop);
    cropped = static_cast<std::size_t>(std::count(inside.begin(), inside.end(), 1));
    return voxel_down_sample(points, options.voxel_size, name, &inside);
  };
  const std::vector<Vec3> source = thinned(reconstruction, names[0], f.reconstruction_cropped);
  const std::vector<Vec3> target = thinned(ground_truth, names[1], f.ground_truth_cropped);
  f.reconstruction_thinned = source.size();
  f.ground_truth_thinned = target.size();
  step(1);
  if (source.empty() || target.empty()) {
    if (clouds) {  // no point to be near: every distance beyond any
      const double none = std::numeric_limits<double>::infinity();
      *clouds = {source, target, std::vector<double>(source.size(), none), std::vector<double>(target.size(), none)};
    }
    step(kSteps);
    return f;
  }
  // nanoflann builds a tree on one core: the two at once.
  std::unique_ptr<PointTree> source_tree, target_tree;
  tbb::parallel_invoke([&] { source_tree = std::make_unique<PointTree>(source); },
                       [&] { target_tree = std::make_unique<PointTree>(target); });
  step(2);
  std::vector<double> precision_distances = target_tree->nearest_distances(source);
  std::vector<double> recall_distances = source_tree->nearest_distances(target);
  f.precision_counted = count_below(precision_distances, options.tau);
  f.recall_counted = count_below(recall_distances, options.tau);
  f.precision = static_cast<double>(f.precision_counted) / static_cast<double>(source.size());
  f.recall = static_cast<double>(f.recall_counted) / static_cast<double>(target.size());
  // The script's expression, in its order (it divides by zero where P + R is 0; the limit is 0).
  f.fscore = f.precision + f.recall > 0 ? 2 * f.recall * f.precision / (f.recall + f.precision) : 0;
  if (clouds) *clouds = {source, target, precision_distances, recall_distances};
  f.edges = histogram_edges(options.tau * options.plot_stretch, options.tau / 100);
  f.cumulative_precision = cumulative_shares(std::move(precision_distances), f.edges);
  f.cumulative_recall = cumulative_shares(std::move(recall_distances), f.edges);
  step(kSteps);
  return f;
}

}  // namespace roving
