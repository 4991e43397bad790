#include "roving/mpeg/point_cloud_psnr.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "roving/core/error.h"
#include "roving/mpeg/lattice_neighbours.h"
#include "roving/mpeg/pc_error_arithmetic.h"
#include "roving/mpeg/pc_error_loop.h"

namespace roving {
namespace {

using Point = std::array<float, 3>;
using PointsAdaptor = MpegPointsAdaptor;
using KdTree = MpegKdTree;  // pc_error's: its figures then agree to the last bit

double squared_distance(const Point& p, const Point& q) { return mpeg_squared_distance(p, q); }

constexpr std::size_t kMaxNeighbours = 30;  // pc_error's bound on the neighbours it looks at

struct Neighbours {
  std::array<std::uint32_t, kMaxNeighbours> index;
  std::array<double, kMaxNeighbours> squared;
  std::size_t found = 0;
};

// The nearest `first` points of `tree` (and 5 more at a time, up to 30, while all found are at the
// nearest distance): pc_error's search, whose extent decides which ties it sees.
Neighbours nearest(const KdTree& tree, std::size_t size, const Point& q, std::size_t first) {
  Neighbours n;
  std::size_t k = std::min(first, size);
  for (;;) {
    n.found = tree.knnSearch(q.data(), k, n.index.data(), n.squared.data());
    const bool all_tied = n.found > 0 && n.squared[0] == n.squared[n.found - 1];
    if (!all_tied || k + 5 > kMaxNeighbours || k >= size) return n;
    k = std::min(k + 5, size);
  }
}

// How many of the nearest points count as one: consecutive squared distances within `threshold`.
std::size_t tied_run(const Neighbours& n, double threshold) {
  std::size_t count = 1;
  while (count < n.found && std::fabs(n.squared[count] - n.squared[count - 1]) < threshold) ++count;
  return count;
}

// The points pc_error's search (nearest(..., 10)) counts as tied with the nearest, found cheaply:
// where the run of ties ends within the nearest 4, it is the same set; else its search runs.
Neighbours nearest_tied(const KdTree& tree, std::size_t size, const Point& q, double threshold) {
  Neighbours n;
  n.found = tree.knnSearch(q.data(), std::min<std::size_t>(4, size), n.index.data(), n.squared.data());
  const std::size_t tied = tied_run(n, threshold);
  if (tied < n.found) {
    n.found = tied;
    return n;
  }
  n = nearest(tree, size, q, 10);
  n.found = tied_run(n, threshold);
  return n;
}

// How many of `tied` points at the nearest distance pc_error's search from `first` neighbours
// (nearest()) sees: it grows by 5 while every point found is at that distance.
std::size_t seen_of_tied(std::size_t first, std::size_t tied, std::size_t size) {
  std::size_t k = std::min(first, size);
  while (tied >= k && k + 5 <= kMaxNeighbours && k < size) k = std::min(k + 5, size);
  return std::min(tied, k);
}

// One thread's room for NearestPoints' lattice queries.
struct Scratch {
  LatticeNeighbours::Probe probe;
  LatticeNeighbours::Shell shell;
  std::vector<std::uint32_t> runs;  // a block's matches, before they are kept at their size
};

// A cloud's nearest points to a query, as pc_error's search finds them. Where both clouds are
// voxelised they come from the lattice (lattice_neighbours.h): its shell is every point at the
// least distance, and as squared distances between integers differ by 1 or more, pc_error's ties
// (within a threshold < 1) are that shell, as far as its search sees; where the search would see
// only some of them (which ones is its tree's choice), where no point is within the lattice's
// reach, and for clouds not voxelised, a k-d tree like pc_error's answers.
class NearestPoints {
 public:
  explicit NearestPoints(const MpegPoints& points) : points_(points), adaptor_{points.positions} {}

  void use_lattice(std::unique_ptr<LatticeNeighbours> lattice) { lattice_ = std::move(lattice); }
  // Frees the search structures once every query has been answered.
  void release() {
    lattice_.reset();
    tree_.reset();
  }
  std::size_t size() const { return points_.size(); }

  // Built on first use: on a lattice, most clouds never need it.
  const KdTree& tree() const {
    std::call_once(built_, [this] {
      tree_ = std::make_unique<KdTree>(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(kMpegTreeLeaf));
    });
    return *tree_;
  }

  // nearest_tied()'s points.
  Neighbours tied(const Point& q, double threshold, Scratch& scratch) const {
    if (lattice_ && lattice_->nearest(q, false, scratch.probe, scratch.shell)) {
      const LatticeNeighbours::Shell& s = scratch.shell;
      if (seen_of_tied(10, s.count, size()) == s.count) return from_shell(s);
    }
    return nearest_tied(tree(), size(), q, threshold);
  }

  // The squared distance to the nearest point.
  double nearest_squared(const Point& q, Scratch& scratch) const {
    if (lattice_ && lattice_->nearest(q, false, scratch.probe, scratch.shell)) return scratch.shell.squared;
    std::uint32_t index;
    double squared;
    tree().knnSearch(q.data(), 1, &index, &squared);
    return squared;
  }

  // pc_error's spacing at point i (largest_spacing()): the distance to its nearest other point
  // where that is over 1e-5, else 0.
  double spacing(std::size_t i, Scratch& scratch) const {
    const Point& q = points_.positions[i];
    if (lattice_ && lattice_->nearest(q, true, scratch.probe, scratch.shell)) return std::sqrt(scratch.shell.squared);
    std::uint32_t index[2];
    double squared[2];
    const std::size_t found = tree().knnSearch(q.data(), 2, index, squared);
    return found == 2 && index[0] == i && squared[1] > 1e-10 ? std::sqrt(squared[1]) : 0.0;
  }

 private:
  static Neighbours from_shell(const LatticeNeighbours::Shell& s) {
    Neighbours n;
    n.found = s.count;
    std::copy_n(s.index.begin(), s.count, n.index.begin());
    std::fill_n(n.squared.begin(), s.count, s.squared);
    return n;
  }

  const MpegPoints& points_;
  PointsAdaptor adaptor_;
  std::unique_ptr<LatticeNeighbours> lattice_;
  mutable std::once_flag built_;
  mutable std::unique_ptr<KdTree> tree_;
};

// Fixed blocks of points, so that sums over them, taken block by block in order, are the same
// whatever the threads.
constexpr std::size_t kBlock = 4096;

template <class Body>
void for_each_block(std::size_t count, const Body& body) {
  tbb::parallel_for(std::size_t{0}, (count + kBlock - 1) / kBlock, [&](std::size_t block) {
    body(block, block * kBlock, std::min(count, (block + 1) * kBlock));
  });
}

// Each point of `from`'s nearest points in `to` (nearest_tied), kept block by block for a second
// pass: A's points carry their normals onto B's, then A -> B's D2 and colour read the same
// points, one search per point instead of two.
struct Matches {
  std::vector<std::uint8_t> tied;                 // the run tied with the nearest (at most kMaxNeighbours)
  std::vector<std::uint8_t> equal;                // how many of the run are exactly as near
  std::vector<std::vector<std::uint32_t>> index;  // per block: each point's run, point after point
};

Matches find_matches(const MpegPoints& from, const NearestPoints& to, double threshold) {
  Matches m;
  m.tied.resize(from.size());
  m.equal.resize(from.size());
  m.index.resize((from.size() + kBlock - 1) / kBlock);
  tbb::enumerable_thread_specific<Scratch> scratches;  // one per thread, for this cloud
  for_each_block(from.size(), [&](std::size_t block, std::size_t begin, std::size_t end) {
    Scratch& scratch = scratches.local();
    scratch.runs.clear();
    for (std::size_t i = begin; i < end; ++i) {
      const Neighbours n = to.tied(from.positions[i], threshold, scratch);
      // The run holds every point exactly as near (a difference of 0 is within any threshold),
      // as far as pc_error's search sees them: its search for the points exactly as near (from 2
      // neighbours, then 5, growing by 5 while all are equal, up to 30) sees as many, the same.
      std::size_t equal = 1;
      while (equal < n.found && n.squared[equal] == n.squared[0]) ++equal;
      m.tied[i] = std::uint8_t(n.found);
      m.equal[i] = std::uint8_t(equal);
      for (std::size_t k = 0; k < n.found; ++k) scratch.runs.push_back(n.index[k]);  // cheaper than insert's checks
    }
    m.index[block].assign(scratch.runs.begin(), scratch.runs.end());
  });
  return m;
}

// A's normals carried onto B's points (see the header), from A's matches in B; B's points that no
// point of A matched take the normals of their own matches in A that are exactly as near.
std::vector<Point> normals_carried(const MpegPoints& a, const MpegPoints& b, const Matches& a_in_b,
                                   const Matches& b_in_a) {
  // Added in A's order: the single-precision sums then round as pc_error's do. On all cores, each
  // adding to its own range of B's points (and reading past the others').
  std::vector<Point> normals(b.size(), Point{0, 0, 0});
  std::vector<int> count(b.size(), 0);
  const std::size_t parts = std::size_t(tbb::this_task_arena::max_concurrency());
  tbb::parallel_for(std::size_t{0}, parts, [&](std::size_t part) {
    const std::uint32_t low = std::uint32_t(b.size() * part / parts), high = std::uint32_t(b.size() * (part + 1) / parts);
    for (std::size_t block = 0; block < a_in_b.index.size(); ++block) {
      const std::uint32_t* run = a_in_b.index[block].data();
      for (std::size_t i = block * kBlock; i < std::min(a.size(), (block + 1) * kBlock); run += a_in_b.tied[i++]) {
        for (std::size_t k = 0; k < a_in_b.equal[i]; ++k) {
          const std::uint32_t j = run[k];
          if (j < low || j >= high) continue;
          for (int c = 0; c < 3; ++c) normals[j][c] += a.normals[i][c];
          ++count[j];
        }
      }
    }
  });
  for_each_block(b.size(), [&](std::size_t block, std::size_t begin, std::size_t end) {
    const std::uint32_t* run = b_in_a.index[block].data();
    for (std::size_t j = begin; j < end; run += b_in_a.tied[j++]) {
      if (count[j] > 0) {
        for (int c = 0; c < 3; ++c) normals[j][c] /= float(count[j]);
        continue;
      }
      for (std::size_t k = 0; k < b_in_a.equal[j]; ++k)
        for (int c = 0; c < 3; ++c) normals[j][c] += a.normals[run[k]][c];
      for (int c = 0; c < 3; ++c) normals[j][c] /= float(b_in_a.equal[j]);
    }
  });
  return normals;
}

// Each point of `from` against `to`: sums and maxima per block, then over the blocks in order.
// `matches`: `from`'s points' matches where found already, else searched here.
MpegDirection direction(const MpegPoints& from, const MpegPoints& to, const NearestPoints& to_nearest,
                        const Matches* matches, const std::vector<Point>* to_normals, bool colour, bool ycocg,
                        double threshold) {
  const bool ties = to_normals || colour;  // D1 needs the nearest point alone
  std::vector<MpegDirection> blocks((from.size() + kBlock - 1) / kBlock);
  tbb::enumerable_thread_specific<Scratch> scratches;  // one per thread, for this cloud
  for_each_block(from.size(), [&](std::size_t block, std::size_t begin, std::size_t end) {
    MpegDirection sum;  // in this frame, so that the compiler may keep it in registers
    Scratch& scratch = scratches.local();
    const std::uint32_t* run = matches ? matches->index[block].data() : nullptr;
    // The matches' points are read at random: those of the point kAhead on are asked for now, so
    // that the reads' cache misses overlap instead of following one another.
    constexpr std::size_t kAhead = 8;
    const std::uint32_t* ahead = run;
    for (std::size_t i = begin; matches && i < std::min(end, begin + kAhead); ++i) ahead += matches->tied[i];
    for (std::size_t i = begin; i < end; ++i) {
      const Point& p = from.positions[i];
      Neighbours n;
      if (matches && i + kAhead < end) {
        const std::uint32_t j = *ahead;
        __builtin_prefetch(&to.positions[j]);
        if (to_normals) __builtin_prefetch(&(*to_normals)[j]);
        if (colour) __builtin_prefetch(&to.colours[j]);
        ahead += matches->tied[i + kAhead];
      }
      if (matches) {
        n.found = matches->tied[i];
        n.squared[0] = squared_distance(p, to.positions[run[0]]);  // as the search computed it
        std::copy_n(run, n.found, n.index.begin());
        run += n.found;
      } else if (ties) {
        n = to_nearest.tied(p, threshold, scratch);
      } else {
        n.found = 1;
        n.squared[0] = to_nearest.nearest_squared(p, scratch);
      }
      sum.d1_mse += n.squared[0];
      sum.d1_hausdorff = std::max(sum.d1_hausdorff, n.squared[0]);
      if (to_normals) {
        // In single precision, as pc_error's sum of products; averaged over the ties.
        double d2 = 0;
        for (std::size_t k = 0; k < n.found; ++k) {
          const Point& q = to.positions[n.index[k]];
          const Point& normal = (*to_normals)[n.index[k]];
          const float e = (p[0] - q[0]) * normal[0] + (p[1] - q[1]) * normal[1] + (p[2] - q[2]) * normal[2];
          d2 += double(e * e);
        }
        d2 /= double(n.found);
        sum.d2_mse += d2;
        sum.d2_hausdorff = std::max(sum.d2_hausdorff, d2);
      }
      if (colour) {
        std::array<std::uint8_t, 3> mean = to.colours[n.index[0]];  // one nearest point: its colour
        if (n.found > 1) {
          unsigned total[3] = {0, 0, 0};
          for (std::size_t k = 0; k < n.found; ++k)
            for (int c = 0; c < 3; ++c) total[c] += to.colours[n.index[k]][c];
          // Rounded half away from zero, as std::round of the quotient: a quotient of integers this
          // small is never nearer a half than 1 / 60, far beyond any rounding of the division.
          const unsigned count = unsigned(n.found);
          for (int c = 0; c < 3; ++c) mean[c] = std::uint8_t((2 * total[c] + count) / (2 * count));
        }
        const std::array<float, 3> in = pc_error_ycbcr(from.colours[i]), met = pc_error_ycbcr(mean);
        if (ycocg) {
          const std::array<float, 3> in8 = pc_error_ycocg(from.colours[i]), met8 = pc_error_ycocg(mean);
          for (int c = 0; c < 3; ++c) sum.ycocg_mse[c] += double((in8[c] - met8[c]) * (in8[c] - met8[c]));
        }
        for (int c = 0; c < 3; ++c) {
          const float dy = in[c] - met[c];
          sum.ycbcr_mse[c] += double(dy * dy);
          const float dc = float(from.colours[i][c]) - float(mean[c]);
          sum.rgb_mse[c] += double(dc * dc);
          sum.rgb_hausdorff[c] = std::max(sum.rgb_hausdorff[c], double(dc * dc));
        }
      }
    }
    blocks[block] = sum;
  });
  MpegDirection d;
  d.points = from.size();
  for (const MpegDirection& b : blocks) {
    d.d1_mse += b.d1_mse;
    d.d1_hausdorff = std::max(d.d1_hausdorff, b.d1_hausdorff);
    d.d2_mse += b.d2_mse;
    d.d2_hausdorff = std::max(d.d2_hausdorff, b.d2_hausdorff);
    for (int c = 0; c < 3; ++c) {
      d.ycbcr_mse[c] += b.ycbcr_mse[c];
      d.rgb_mse[c] += b.rgb_mse[c];
      d.ycocg_mse[c] += b.ycocg_mse[c];
      d.rgb_hausdorff[c] = std::max(d.rgb_hausdorff[c], b.rgb_hausdorff[c]);
    }
  }
  const double count = double(from.size());
  d.d1_mse /= count;
  d.d2_mse /= count;
  for (int c = 0; c < 3; ++c) {
    d.ycbcr_mse[c] /= count;
    d.rgb_mse[c] /= count;
    d.ycocg_mse[c] /= count;
  }
  return d;
}

// pc_error's default peak: the largest distance from a point of A to its nearest other point,
// leaving out points with another within 1e-5.
std::optional<double> largest_spacing(const MpegPoints& a, const NearestPoints& a_nearest) {
  std::vector<double> spacing(a.size(), 0);
  tbb::enumerable_thread_specific<Scratch> scratches;  // one per thread, for this cloud
  for_each_block(a.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
    Scratch& scratch = scratches.local();
    for (std::size_t i = begin; i < end; ++i) spacing[i] = a_nearest.spacing(i, scratch);
  });
  const double largest = *std::max_element(spacing.begin(), spacing.end());
  if (largest > 0) return largest;
  return std::nullopt;
}

}  // namespace

MpegDirection MpegFigures::symmetric() const {
  MpegDirection worse;
  worse.points = std::max(a_to_b.points, b_to_a.points);
  worse.d1_mse = std::max(a_to_b.d1_mse, b_to_a.d1_mse);
  worse.d1_hausdorff = std::max(a_to_b.d1_hausdorff, b_to_a.d1_hausdorff);
  worse.d2_mse = std::max(a_to_b.d2_mse, b_to_a.d2_mse);
  worse.d2_hausdorff = std::max(a_to_b.d2_hausdorff, b_to_a.d2_hausdorff);
  for (int c = 0; c < 3; ++c) {
    worse.ycbcr_mse[c] = std::max(a_to_b.ycbcr_mse[c], b_to_a.ycbcr_mse[c]);
    worse.rgb_mse[c] = std::max(a_to_b.rgb_mse[c], b_to_a.rgb_mse[c]);
    worse.ycocg_mse[c] = std::max(a_to_b.ycocg_mse[c], b_to_a.ycocg_mse[c]);
    worse.rgb_hausdorff[c] = std::max(a_to_b.rgb_hausdorff[c], b_to_a.rgb_hausdorff[c]);
  }
  return worse;
}

double geometry_psnr(double mse, double peak) { return 10 * std::log10(3 * peak * peak / mse); }

double colour_psnr(double mse, double peak) { return 10 * std::log10(peak * peak / mse); }

// mmetric's default peak: the diagonal of A's box, in single precision.
double box_diagonal(const MpegPoints& a) {
  Point low = a.positions.front(), high = low;
  for (const Point& p : a.positions) {
    for (int c = 0; c < 3; ++c) low[c] = std::min(low[c], p[c]), high[c] = std::max(high[c], p[c]);
  }
  const float x = high[0] - low[0], y = high[1] - low[1], z = high[2] - low[2];
  return double(std::sqrt(x * x + y * y + z * z));
}

MpegFigures mpeg_point_cloud_figures(const MpegPoints& a, const MpegPoints& b, const MpegRules& rules,
                                     const std::string& a_name) {
  const std::optional<double>& resolution = rules.resolution;
  if (resolution && !(*resolution >= std::numeric_limits<float>::min() &&
                      *resolution <= std::numeric_limits<float>::max())) {
    throw Error(fmt::format("--pcc-resolution: expected a peak > 0 that single precision holds, found {}", *resolution));
  }
  const PcErrorOptions& options = rules.options;
  if (!(options.dropdups >= 0 && options.dropdups <= 2) ||
      !(options.neighbors_proc >= 0 && options.neighbors_proc <= 4)) {
    throw Error(fmt::format("--pcc-dropdups {}, --pcc-neighbors-proc {}: expected 0 to 2 and 0 to 4", options.dropdups,
                            options.neighbors_proc));
  }
  // pc_error's own loop where the search below does not follow it: its other options, NaN normals.
  const bool literal = !options.defaults() || a.nan_normals > 0;
  NearestPoints a_nearest(a), b_nearest(b);
  std::unique_ptr<LatticeNeighbours> a_lattice, b_lattice;
  if (!literal) {
    tbb::parallel_invoke([&] { a_lattice = LatticeNeighbours::build(a.positions); },
                         [&] { b_lattice = LatticeNeighbours::build(b.positions); });
  }
  if (a_lattice && b_lattice) {  // both voxelised: queries from either are on the lattice
    a_nearest.use_lattice(std::move(a_lattice));
    b_nearest.use_lattice(std::move(b_lattice));
  } else if (!literal) {
    tbb::parallel_invoke([&] { a_nearest.tree(); }, [&] { b_nearest.tree(); });
  }

  MpegFigures figures;
  figures.mmetric = rules.mmetric;
  figures.peak_given = resolution.has_value();
  if (resolution) {
    // pc_error reads --resolution as a float.
    figures.peak = double(float(*resolution));
  } else if (rules.mmetric) {
    figures.peak = box_diagonal(a);
    if (!(figures.peak > 0)) {
      throw Error(fmt::format("{}: its samples have no extent, so there is no diagonal to take as the PSNR's "
                              "peak; give --pcc-resolution",
                              a_name));
    }
  } else {
    const std::optional<double> spacing = largest_spacing(a, a_nearest);
    if (!spacing) {
      throw Error(fmt::format(
          "{}: no two points are 1e-5 or more apart, so there is no spacing to take as the PSNR's peak; "
          "give --pcc-resolution",
          a_name));
    }
    figures.peak = *spacing;
  }
  figures.d2 = !a.normals.empty();
  figures.colour = !a.colours.empty() && !b.colours.empty();
  figures.ycocg = figures.colour && options.ycocg;
  // B's normals for A -> B: mmetric takes B's own where it has them, pc_error carries A's over.
  std::vector<Point> carried;
  const bool own = rules.b_normals_own() && !b.normals.empty();
  const double threshold = rules.tie_threshold();
  if (literal) {
    a_nearest.release();
    b_nearest.release();
    pc_error_directions(a, b, own ? &b.normals : nullptr, options, threshold, figures);
    return figures;
  }
  // Each direction's matches are searched once: B's in A serve B -> A and the points of B that
  // no point of A matched, A's in B carry A's normals over and serve A -> B.
  std::optional<Matches> a_in_b, b_in_a;
  if (figures.d2 || figures.colour) {
    b_in_a = find_matches(b, a_nearest, threshold);
    a_nearest.release();  // B -> A reads these matches, and nothing else searches A: its room is A's in B's
  }
  if (figures.d2 && !own) {
    a_in_b = find_matches(a, b_nearest, threshold);
    // Both directions have their matches: the searches' room goes to the carried normals.
    b_nearest.release();
    carried = normals_carried(a, b, *a_in_b, *b_in_a);
  }
  const std::vector<Point>* b_normals = !figures.d2 ? nullptr : own ? &b.normals : &carried;
  figures.a_to_b = direction(a, b, b_nearest, a_in_b ? &*a_in_b : nullptr, b_normals, figures.colour,
                             figures.ycocg, threshold);
  a_in_b.reset();
  figures.b_to_a = direction(b, a, a_nearest, b_in_a ? &*b_in_a : nullptr, figures.d2 ? &a.normals : nullptr,
                             figures.colour, figures.ycocg, threshold);
  return figures;
}

}  // namespace roving
