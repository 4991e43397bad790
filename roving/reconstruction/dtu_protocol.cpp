#include "roving/reconstruction/dtu_protocol.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <memory>
#include <numeric>
#include <random>

#include "roving/core/error.h"
#include "roving/reconstruction/greedy_thinning.h"
#include "roving/reconstruction/point_tree.h"

namespace roving {
namespace {

constexpr std::size_t kMaxPoints = 1000000000;

// A uniform integer in [0, bound) from a 64-bit generator, without bias (Lemire's method), so that
// a seed gives the same order on every platform (std's distributions may differ between them).
std::uint64_t below(std::mt19937_64& random, std::uint64_t bound) {
  unsigned __int128 m = static_cast<unsigned __int128>(random()) * bound;
  if (static_cast<std::uint64_t>(m) < bound) {
    const std::uint64_t floor = (0 - bound) % bound;
    while (static_cast<std::uint64_t>(m) < floor) m = static_cast<unsigned __int128>(random()) * bound;
  }
  return static_cast<std::uint64_t>(m >> 64);
}

// Each point's place in the visiting order: a Fisher-Yates shuffle of the points' own order under
// `seed`, or that order itself.
std::vector<std::uint32_t> visiting_rank(std::size_t count, std::optional<std::uint64_t> seed) {
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  if (!seed) return order;
  std::mt19937_64 random(*seed);
  for (std::size_t i = count; i > 1; --i) std::swap(order[i - 1], order[below(random, i)]);
  std::vector<std::uint32_t> rank(count);
  for (std::size_t k = 0; k < count; ++k) rank[order[k]] = static_cast<std::uint32_t>(k);
  return rank;
}

// The mean of the nearest distances from `from` to the tree's points below max_dist, and how many were.
std::pair<double, std::size_t> mean_nearest(const std::vector<Vec3>& from, const PointTree& to, double max_dist) {
  if (to.points().empty() || from.empty()) return {std::numeric_limits<double>::quiet_NaN(), 0};
  double sum = 0;  // in order: the same figure on any number of threads
  std::size_t counted = 0;
  for (const double d : to.nearest_distances(from)) {
    if (d < max_dist) {
      sum += d;
      ++counted;
    }
  }
  return {counted ? sum / counted : std::numeric_limits<double>::quiet_NaN(), counted};
}

// One axis of the script's box in single precision, as NumPy computes it: BB.astype(np.float32),
// then BB - patch and BB + 2 patch in float32; the grid's origin is the rounded BB too.
struct SingleBox {
  double low, high, origin;
};

// Out of line on purpose: inlined in dtu_figures' loop, GCC 12's vectorizer stored the origin
// without its rounding to float (one point of 6 M left the mask on a 10^7-point scene).
[[gnu::noinline]] SingleBox single_box(double min, double max, double patch) {
  const float low = static_cast<float>(min), high = static_cast<float>(max);
  return {static_cast<float>(low - static_cast<float>(patch)), static_cast<float>(high + static_cast<float>(patch * 2)),
          low};
}

// The script's grid on one face: n1 x n2 steps along its edges from the first corner (0 x 0 for a
// face of zero area, which gets no point).
struct FaceGrid {
  double n1 = 0, n2 = 0;
};

FaceGrid face_grid(const Vec3& a, const Vec3& b, const Vec3& c, double density) {
  const Vec3 v1 = b - a, v2 = c - a;
  const double l1 = std::sqrt(v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2]);
  const double l2 = std::sqrt(v2[0] * v2[0] + v2[1] * v2[1] + v2[2] * v2[2]);
  const Vec3 n(v1[1] * v2[2] - v1[2] * v2[1], v1[2] * v2[0] - v1[0] * v2[2], v1[0] * v2[1] - v1[1] * v2[0]);
  const double area2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(area2 > 0)) return {};
  const double step = density * std::sqrt(l1 * l2 / area2);
  return {std::floor(l1 / step), std::floor(l2 / step)};
}

// The grid's points strictly inside the face, (k1, k2) = ((i + 0.5) / n1, (j + 0.5) / n2) with
// k1 + k2 < 1, in the script's order (i, then j), each given to `emit`; returns how many.
template <typename Emit>
std::size_t for_each_grid_point(const FaceGrid& grid, Emit&& emit) {
  if (grid.n1 == 0 || grid.n2 == 0) return 0;  // the script's 1e-7 puts every point outside the face
  std::size_t count = 0;
  for (double i = 0; i <= grid.n1; ++i) {
    const double k1 = (i + 0.5) / grid.n1;
    for (double j = 0; j <= grid.n2; ++j) {
      const double k2 = (j + 0.5) / grid.n2;
      if (!(k1 + k2 < 1)) break;  // k2 grows with j
      emit(k1, k2);
      ++count;
    }
  }
  return count;
}

void require_positive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0)) {
    throw Error(fmt::format("the DTU protocol's {} must be finite and > 0; found {}", what, value));
  }
}

}  // namespace

std::vector<Vec3> dtu_mesh_points(const TriangleMesh& mesh, const std::string& name, double density,
                                  std::size_t* samples) {
  require_positive(density, "density");
  const SharedArray<Vec3>& v = mesh.positions();
  const SharedArray<Triangle>& faces = mesh.triangles();
  const auto too_many = [&] {
    return Error(fmt::format("{}: sampling it every {} (the DTU protocol's density) would make over {} points; "
                             "is it in millimetres, as DTU's models are?",
                             name, density, kMaxPoints));
  };
  // Each face's grid and its count first (in parallel), so that every point has its place before
  // any is made, and an absurd count is refused before it is allocated.
  std::vector<FaceGrid> grids(faces.size());
  std::vector<std::size_t> offsets(faces.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 1024), [&](const auto& range) {
    for (std::size_t f = range.begin(); f < range.end(); ++f) {
      grids[f] = face_grid(v[faces[f][0]], v[faces[f][1]], v[faces[f][2]], density);
      if (!((grids[f].n1 + 1) * (grids[f].n2 + 1) < double(kMaxPoints))) throw too_many();
      offsets[f + 1] = for_each_grid_point(grids[f], [](double, double) {});
    }
  });
  offsets[0] = v.size();
  for (std::size_t f = 0; f < faces.size(); ++f) {
    offsets[f + 1] += offsets[f];
    if (offsets[f + 1] > kMaxPoints) throw too_many();
  }
  std::vector<Vec3> points(offsets.back());
  std::copy(v.begin(), v.end(), points.begin());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 1024), [&](const auto& range) {
    for (std::size_t f = range.begin(); f < range.end(); ++f) {
      const Vec3 &a = v[faces[f][0]], v1 = v[faces[f][1]] - a, v2 = v[faces[f][2]] - a;
      Vec3* out = &points[offsets[f]];
      for_each_grid_point(grids[f], [&](double k1, double k2) {
        *out++ = Vec3(v1[0] * k1 + v2[0] * k2 + a[0], v1[1] * k1 + v2[1] * k2 + a[1], v1[2] * k1 + v2[2] * k2 + a[2]);
      });
    }
  });
  if (samples) *samples = points.size() - v.size();
  return points;
}

DtuRegion::DtuRegion(const DtuObservationMask& mask, const std::array<double, 4>& plane, double patch)
    : mask_(mask), plane_(plane) {
  if (!(std::isfinite(patch) && patch >= 0)) {
    throw Error(fmt::format("the DTU protocol's patch must be finite and >= 0; found {}", patch));
  }
  require_positive(mask.resolution, "mask resolution (Res)");
  if (mask.observed.size() != mask.dims[0] * mask.dims[1] * mask.dims[2]) {
    throw Error(fmt::format("the DTU observation mask holds {} values for its {} x {} x {} voxels",
                            mask.observed.size(), mask.dims[0], mask.dims[1], mask.dims[2]));
  }
  for (int a = 0; a < 3; ++a) {
    const SingleBox box = single_box(mask.box_min[a], mask.box_max[a], patch);
    low_[a] = box.low, high_[a] = box.high, origin_[a] = box.origin;
  }
}

bool DtuRegion::in_box(const Vec3& p) const {
  return p[0] >= low_[0] && p[1] >= low_[1] && p[2] >= low_[2] && p[0] < high_[0] && p[1] < high_[1] && p[2] < high_[2];
}

bool DtuRegion::observed(const Vec3& p) const {
  if (!in_box(p)) return false;
  std::array<std::size_t, 3> cell;
  for (int a = 0; a < 3; ++a) {
    // np.around: halves to even, as nearbyint in the default rounding mode.
    const double g = std::nearbyint((p[a] - origin_[a]) / mask_.resolution);
    if (!(g >= 0 && g < double(mask_.dims[a]))) return false;
    cell[a] = static_cast<std::size_t>(g);
  }
  return mask_.observed[cell[0] + mask_.dims[0] * (cell[1] + mask_.dims[1] * cell[2])] != 0;
}

bool DtuRegion::above(const Vec3& p) const {
  return plane_[0] * p[0] + plane_[1] * p[1] + plane_[2] * p[2] + plane_[3] > 0;
}

DtuFigures dtu_figures(const std::vector<Vec3>& reconstruction, const std::vector<Vec3>& ground_truth,
                       const DtuObservationMask& mask, const std::array<double, 4>& plane, const DtuOptions& options,
                       const ProgressFn& progress) {
  require_positive(options.density, "density");
  require_positive(options.max_dist, "max_dist");
  if (reconstruction.size() > std::numeric_limits<std::uint32_t>::max() - 1) {
    throw Error(fmt::format("the DTU protocol takes at most {} points; found {}",
                            std::numeric_limits<std::uint32_t>::max() - 1, reconstruction.size()));
  }
  DtuFigures figures;
  figures.options = options;
  figures.reconstruction_points = reconstruction.size();
  figures.ground_truth_points = ground_truth.size();
  const DtuRegion region(mask, plane, options.patch);
  std::vector<Vec3> above;
  for (const Vec3& p : ground_truth) {
    if (region.above(p)) above.push_back(p);
  }
  figures.ground_truth_above = above.size();
  const int runs = options.first_seed ? std::max(options.runs, 1) : 1;
  // The ground truth's tree is built on the other core while the first run thins.
  // In spatial order: a data set's ground truth comes in its scanner's order, or at random.
  std::future<std::unique_ptr<PointTree>> building = std::async(
      std::launch::async, [&] { return std::make_unique<PointTree>(ground_truth, PointTree::Layout::InSpace); });
  std::unique_ptr<PointTree> truth_tree;
  for (int run = 0; run < runs; ++run) {
    // Three steps a run: thinning, masking and the accuracy queries, the completeness queries.
    const auto step = [&](int done) {
      if (progress) progress("protocol steps", static_cast<std::size_t>(3 * run + done), static_cast<std::size_t>(3 * runs));
    };
    step(0);
    DtuRun r;
    if (options.first_seed) r.seed = *options.first_seed + static_cast<std::uint64_t>(run);
    const std::vector<std::uint8_t> keep =
        greedy_thinning(reconstruction, visiting_rank(reconstruction.size(), r.seed), options.density);
    r.thinned = static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
    // The kept points in their own order, not the visiting order: the queries below then walk the
    // trees coherently (the figures are sums, the same in any order but for rounding).
    std::vector<Vec3> in_box, observed;
    in_box.reserve(r.thinned);
    observed.reserve(r.thinned);
    for (std::size_t i = 0; i < keep.size(); ++i) {
      if (!keep[i]) continue;
      const Vec3& p = reconstruction[i];
      if (!region.in_box(p)) continue;
      in_box.push_back(p);
      if (region.observed(p)) observed.push_back(p);
    }
    r.in_box = in_box.size();
    r.observed = observed.size();
    step(1);
    if (!truth_tree) truth_tree = building.get();
    // Accuracy's queries on the ground truth while the tree of the points in the box is built.
    std::unique_ptr<PointTree> box_tree;
    tbb::parallel_invoke(
        [&] { std::tie(r.accuracy, r.accuracy_counted) = mean_nearest(observed, *truth_tree, options.max_dist); },
        [&] { box_tree = std::make_unique<PointTree>(in_box, PointTree::Layout::InSpace); });
    step(2);
    std::tie(r.completeness, r.completeness_counted) = mean_nearest(above, *box_tree, options.max_dist);
    r.overall = (r.accuracy + r.completeness) / 2;
    figures.runs.push_back(r);
  }
  return figures;
}

}  // namespace roving
