#include "roving/reconstruction/dtu_protocol.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>
#include <random>
#include <unordered_map>

#include "roving/core/error.h"

namespace roving {
namespace {

struct PointsAdaptor {
  const std::vector<Vec3>& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::uint32_t i, std::size_t axis) const { return points[i][axis]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>,
                                                   PointsAdaptor, 3, std::uint32_t>;

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

std::vector<std::uint32_t> visiting_order(std::size_t count, std::optional<std::uint64_t> seed) {
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  if (!seed) return order;
  std::mt19937_64 random(*seed);
  for (std::size_t i = count; i > 1; --i) std::swap(order[i - 1], order[below(random, i)]);
  return order;
}

// The script's thinning: visiting points in `order`, each is kept unless a point kept before it is
// within `radius` (squared distance <= radius^2, as scikit-learn's radius query tests it).
// Kept points are found through a hash grid of cells 2 * radius wide: a ball meets at most two
// cells per axis. Cells that share a hash share a list, which costs time, never a wrong answer.
std::vector<std::uint32_t> thinned(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& order,
                                   double radius) {
  const double cell = 2 * radius, r2 = radius * radius;
  const auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto bits = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & ((1u << 21) - 1); };
    return bits(x) | bits(y) << 21 | bits(z) << 42;
  };
  std::unordered_map<std::uint64_t, std::uint32_t> head;  // cell -> last kept point in it, +1
  std::vector<std::uint32_t> next(points.size(), 0), kept;
  for (const std::uint32_t i : order) {
    const Vec3& p = points[i];
    std::array<std::int64_t, 3> lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<std::int64_t>(std::floor((p[a] - radius) / cell));
      hi[a] = static_cast<std::int64_t>(std::floor((p[a] + radius) / cell));
    }
    bool near = false;
    for (std::int64_t x = lo[0]; x <= hi[0] && !near; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1] && !near; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2] && !near; ++z) {
          const auto found = head.find(key(x, y, z));
          for (std::uint32_t j = found == head.end() ? 0 : found->second; j != 0 && !near; j = next[j - 1]) {
            const Vec3& q = points[j - 1];
            const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            near = dx * dx + dy * dy + dz * dz <= r2;
          }
        }
    if (near) continue;
    kept.push_back(i);
    const auto c = [&](int a) { return static_cast<std::int64_t>(std::floor(p[a] / cell)); };
    std::uint32_t& first = head[key(c(0), c(1), c(2))];
    next[i] = first;
    first = i + 1;
  }
  return kept;
}

// The mean of the nearest distances from `from` to `to` below max_dist, and how many were.
std::pair<double, std::size_t> mean_nearest(const std::vector<Vec3>& from, const std::vector<Vec3>& to,
                                            double max_dist) {
  if (to.empty() || from.empty()) return {std::numeric_limits<double>::quiet_NaN(), 0};
  const PointsAdaptor adaptor{to};
  const KdTree tree(3, adaptor, {10});
  std::vector<double> distance(from.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, from.size(), 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      std::uint32_t index = 0;
      double squared = 0;
      tree.knnSearch(from[i].data(), 1, &index, &squared);
      distance[i] = std::sqrt(squared);
    }
  });
  double sum = 0;  // in order: the same figure on any number of threads
  std::size_t counted = 0;
  for (const double d : distance) {
    if (d < max_dist) {
      sum += d;
      ++counted;
    }
  }
  return {counted ? sum / counted : std::numeric_limits<double>::quiet_NaN(), counted};
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
  const std::vector<Vec3>& v = mesh.positions();
  struct Grid {
    double n1, n2;
  };
  // The grid of each face first, so that the count is known (and bounded) before any point is made.
  std::vector<Grid> grids(mesh.triangles().size());
  std::size_t total = v.size();
  for (std::size_t f = 0; f < grids.size(); ++f) {
    const Triangle& t = mesh.triangles()[f];
    const Vec3 v1 = v[t[1]] - v[t[0]], v2 = v[t[2]] - v[t[0]];
    const double l1 = std::sqrt(v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2]);
    const double l2 = std::sqrt(v2[0] * v2[0] + v2[1] * v2[1] + v2[2] * v2[2]);
    const Vec3 c(v1[1] * v2[2] - v1[2] * v2[1], v1[2] * v2[0] - v1[0] * v2[2], v1[0] * v2[1] - v1[1] * v2[0]);
    const double area2 = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(area2 > 0)) {
      grids[f] = {0, 0};
      continue;
    }
    const double step = density * std::sqrt(l1 * l2 / area2);
    grids[f] = {std::floor(l1 / step), std::floor(l2 / step)};
    // Grid points with (i + 0.5) / n1 + (j + 0.5) / n2 < 1: at most (n1 + 1) (n2 + 1) / 2 + n.
    const double most = (grids[f].n1 + 1) * (grids[f].n2 + 1);
    if (!(most < double(kMaxPoints)) || (total += static_cast<std::size_t>(most)) > 2 * kMaxPoints) {
      throw Error(fmt::format("{}: sampling it every {} (the DTU protocol's density) would make over {} points; "
                              "is it in millimetres, as DTU's models are?",
                              name, density, kMaxPoints));
    }
  }
  std::vector<Vec3> points(v.begin(), v.end());
  for (std::size_t f = 0; f < grids.size(); ++f) {
    const auto [n1, n2] = grids[f];
    if (n1 == 0 || n2 == 0) continue;  // the script's 1e-7 puts every point outside the face
    const Triangle& t = mesh.triangles()[f];
    const Vec3 &a = v[t[0]], v1 = v[t[1]] - a, v2 = v[t[2]] - a;
    for (double i = 0; i <= n1; ++i) {
      const double k1 = (i + 0.5) / n1;
      for (double j = 0; j <= n2; ++j) {
        const double k2 = (j + 0.5) / n2;
        if (!(k1 + k2 < 1)) continue;
        points.emplace_back(v1[0] * k1 + v2[0] * k2 + a[0], v1[1] * k1 + v2[1] * k2 + a[1],
                            v1[2] * k1 + v2[2] * k2 + a[2]);
      }
    }
    if (points.size() > kMaxPoints) {
      throw Error(fmt::format("{}: sampling it every {} (the DTU protocol's density) makes over {} points; "
                              "is it in millimetres, as DTU's models are?",
                              name, density, kMaxPoints));
    }
  }
  if (samples) *samples = points.size() - v.size();
  return points;
}

DtuFigures dtu_figures(const std::vector<Vec3>& reconstruction, const std::vector<Vec3>& ground_truth,
                       const DtuObservationMask& mask, const std::array<double, 4>& plane, const DtuOptions& options) {
  require_positive(options.density, "density");
  require_positive(options.max_dist, "max_dist");
  if (!(std::isfinite(options.patch) && options.patch >= 0)) {
    throw Error(fmt::format("the DTU protocol's patch must be finite and >= 0; found {}", options.patch));
  }
  require_positive(mask.resolution, "mask resolution (Res)");
  if (mask.observed.size() != mask.dims[0] * mask.dims[1] * mask.dims[2]) {
    throw Error(fmt::format("the DTU observation mask holds {} values for its {} x {} x {} voxels",
                            mask.observed.size(), mask.dims[0], mask.dims[1], mask.dims[2]));
  }
  if (reconstruction.size() > std::numeric_limits<std::uint32_t>::max() - 1) {
    throw Error(fmt::format("the DTU protocol takes at most {} points; found {}",
                            std::numeric_limits<std::uint32_t>::max() - 1, reconstruction.size()));
  }
  DtuFigures figures;
  figures.options = options;
  figures.reconstruction_points = reconstruction.size();
  figures.ground_truth_points = ground_truth.size();
  std::vector<Vec3> above;
  for (const Vec3& p : ground_truth) {
    if (plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] + plane[3] > 0) above.push_back(p);
  }
  figures.ground_truth_above = above.size();
  // The box in single precision, as the script makes it (BB.astype(np.float32), then float32 sums).
  std::array<double, 3> low, high, origin;
  for (int a = 0; a < 3; ++a) {
    const float min = static_cast<float>(mask.box_min[a]), max = static_cast<float>(mask.box_max[a]);
    low[a] = static_cast<float>(min - static_cast<float>(options.patch));
    high[a] = static_cast<float>(max + static_cast<float>(options.patch * 2));
    origin[a] = min;
  }
  const int runs = options.first_seed ? std::max(options.runs, 1) : 1;
  for (int run = 0; run < runs; ++run) {
    DtuRun r;
    if (options.first_seed) r.seed = *options.first_seed + static_cast<std::uint64_t>(run);
    const std::vector<std::uint32_t> kept = thinned(reconstruction, visiting_order(reconstruction.size(), r.seed),
                                                    options.density);
    r.thinned = kept.size();
    std::vector<Vec3> in_box, observed;
    for (const std::uint32_t i : kept) {
      const Vec3& p = reconstruction[i];
      if (!(p[0] >= low[0] && p[1] >= low[1] && p[2] >= low[2] && p[0] < high[0] && p[1] < high[1] &&
            p[2] < high[2])) {
        continue;
      }
      in_box.push_back(p);
      std::array<std::size_t, 3> cell;
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        // np.around: halves to even, as nearbyint in the default rounding mode.
        const double g = std::nearbyint((p[a] - origin[a]) / mask.resolution);
        inside = inside && g >= 0 && g < double(mask.dims[a]);
        cell[a] = inside ? static_cast<std::size_t>(g) : 0;
      }
      if (inside && mask.observed[cell[0] + mask.dims[0] * (cell[1] + mask.dims[1] * cell[2])]) observed.push_back(p);
    }
    r.in_box = in_box.size();
    r.observed = observed.size();
    std::tie(r.accuracy, r.accuracy_counted) = mean_nearest(observed, ground_truth, options.max_dist);
    std::tie(r.completeness, r.completeness_counted) = mean_nearest(above, in_box, options.max_dist);
    r.overall = (r.accuracy + r.completeness) / 2;
    figures.runs.push_back(r);
  }
  return figures;
}

}  // namespace roving
