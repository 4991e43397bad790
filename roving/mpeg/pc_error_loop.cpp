#include "roving/mpeg/pc_error_loop.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "roving/mpeg/pc_error_arithmetic.h"

namespace roving {
namespace {

using Point = std::array<float, 3>;
using Colour = std::array<std::uint8_t, 3>;

constexpr std::size_t kMaxNeighbours = 30;  // pc_error's num_results_max
constexpr std::size_t kGrowth = 5;          // its num_results_incr

struct Search {
  std::array<std::uint32_t, kMaxNeighbours> index;
  std::array<double, kMaxNeighbours> squared;
  std::size_t found = 0;
};

// pc_error's search from `first` points, grown by 5 while every point found is as near as the
// nearest (where `grow`: its bAverageNormals), up to 30.
Search search(const MpegKdTree& tree, std::size_t size, const Point& q, std::size_t first, bool grow) {
  Search s;
  for (std::size_t k = first;; k += kGrowth) {
    s.found = tree.knnSearch(q.data(), std::min(k, size), s.index.data(), s.squared.data());
    if (!(grow && s.squared[0] == s.squared[s.found - 1] && k + kGrowth <= kMaxNeighbours && k < size)) return s;
  }
}

bool has_nan(const Point& n) { return std::isnan(n[0]) || std::isnan(n[1]) || std::isnan(n[2]); }

struct Tree {
  MpegPointsAdaptor adaptor;
  MpegKdTree tree;
  std::size_t size;
  explicit Tree(const MpegPoints& points)
      : adaptor{points.positions},
        tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kMpegTreeLeaf)),
        size(points.size()) {}
  Search find(const Point& q, std::size_t first, bool grow) const { return search(tree, size, q, first, grow); }
};

// scaleNormals: each point of A adds its normal to its nearest points of B (all exactly as near,
// from a search of 5 that grows; or the first found of 1), in A's order, in single precision; each
// B point's sum divided by how many; a B point none reached takes the mean of its own nearest
// points' normals in A (or the first found's).
std::vector<Point> carried_normals(const MpegPoints& a, const Tree& a_tree, const MpegPoints& b, const Tree& b_tree,
                                   bool average) {
  // Each A point's B points exactly as near, found block by block on all cores and kept compactly
  // (a count and the indices), then added in A's order.
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (a.size() + kBlock - 1) / kBlock;
  std::vector<std::vector<std::uint32_t>> tied(blocks);
  std::vector<std::uint8_t> tied_count(a.size());
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t block) {
    for (std::size_t i = block * kBlock; i < std::min(a.size(), (block + 1) * kBlock); ++i) {
      const Search s = average ? b_tree.find(a.positions[i], kGrowth, true) : b_tree.find(a.positions[i], 1, false);
      std::size_t k = 0;
      for (; k < s.found && s.squared[k] == s.squared[0]; ++k) tied[block].push_back(s.index[k]);
      tied_count[i] = std::uint8_t(k);
    }
  });
  std::vector<Point> normals(b.size(), Point{0, 0, 0});
  std::vector<int> count(b.size(), 0);
  for (std::size_t block = 0; block < blocks; ++block) {  // in A's order: the sums round as pc_error's
    const std::uint32_t* run = tied[block].data();
    for (std::size_t i = block * kBlock; i < std::min(a.size(), (block + 1) * kBlock); run += tied_count[i++]) {
      for (std::size_t k = 0; k < tied_count[i]; ++k) {
        for (int c = 0; c < 3; ++c) normals[run[k]][c] += a.normals[i][c];
        ++count[run[k]];
      }
    }
    tied[block] = {};
  }
  tbb::parallel_for(std::size_t{0}, b.size(), [&](std::size_t j) {
    Point& n = normals[j];
    if (count[j] > 0) {
      for (int c = 0; c < 3; ++c) n[c] = n[c] / float(count[j]);
      return;
    }
    const Search s = average ? a_tree.find(b.positions[j], kGrowth, true) : a_tree.find(b.positions[j], 1, false);
    if (!average) {
      n = a.normals[s.index[0]];
      return;
    }
    std::size_t num = 0;
    for (std::size_t k = 0; k < s.found; ++k) {
      if (s.squared[k] != s.squared[0]) continue;
      for (int c = 0; c < 3; ++c) n[c] += a.normals[s.index[k]][c];
      ++num;
    }
    for (int c = 0; c < 3; ++c) n[c] /= float(num);
  });
  return normals;
}

// The squared difference of two colours in RGB, in pc_error's integers.
unsigned rgb_distance(const Colour& x, const Colour& y) {
  unsigned sum = 0;
  for (int c = 0; c < 3; ++c) sum += unsigned((int(x[c]) - int(y[c])) * (int(x[c]) - int(y[c])));
  return sum;
}

// findMetric's colour for point `mine` from the tied points `tied` of `to` (neighborsProc).
Colour matched_colour(const Colour& mine, const MpegPoints& to, const std::uint32_t* tied, std::size_t count,
                      std::uint32_t first, int neighbors_proc) {
  switch (neighbors_proc) {
    case 1:
    case 2: {  // the mean, each point weighted by the points it merged (1 unless neighborsProc 2)
      unsigned total[3] = {0, 0, 0};
      unsigned weights = 0;
      for (std::size_t k = 0; k < count; ++k) {
        const unsigned w = to.merged.empty() ? 1 : to.merged[tied[k]];
        for (int c = 0; c < 3; ++c) total[c] += w * to.colours[tied[k]][c];
        weights += w;
      }
      Colour mean;
      for (int c = 0; c < 3; ++c) mean[c] = std::uint8_t(std::round(double(total[c]) / weights));
      return mean;
    }
    case 3: {  // the nearest in RGB, the first found of equals
      unsigned least = std::numeric_limits<unsigned>::max();
      std::uint32_t chosen = 0;
      for (std::size_t k = 0; k < count; ++k) {
        const unsigned d = rgb_distance(mine, to.colours[tied[k]]);
        if (d < least) least = d, chosen = tied[k];
      }
      return to.colours[chosen];
    }
    case 4: {  // the farthest in RGB; where every one is the point's own colour, pc_error's loop
               // leaves its index at 0 and takes the colour of the cloud's first point
      unsigned most = 0;
      std::uint32_t chosen = 0;
      for (std::size_t k = 0; k < count; ++k) {
        const unsigned d = rgb_distance(mine, to.colours[tied[k]]);
        if (d > most) most = d, chosen = tied[k];
      }
      return to.colours[chosen];
    }
    default:  // 0: the first found
      return to.colours[first];
  }
}

// findMetric: each point of `from` against `to`, sums per block of points added in order.
MpegDirection direction(const MpegPoints& from, const MpegPoints& to, const Tree& to_tree,
                        const std::vector<Point>* to_normals, const PcErrorOptions& options, double threshold,
                        const MpegFigures& figures) {
  constexpr std::size_t kBlock = 4096;  // as point_cloud_psnr's, so that the sums round alike
  const bool colour = figures.colour;
  std::vector<MpegDirection> blocks((from.size() + kBlock - 1) / kBlock);
  tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t block) {
    MpegDirection sum;
    for (std::size_t i = block * kBlock; i < std::min(from.size(), (block + 1) * kBlock); ++i) {
      const Point& p = from.positions[i];
      const Search s = to_tree.find(p, 2 * kGrowth, options.average_normals);
      const std::uint32_t j = s.index[0];
      std::size_t tied = 1;  // sameDistPoints: consecutive squared distances within the threshold
      while (tied < s.found && std::fabs(s.squared[tied] - s.squared[tied - 1]) < threshold) ++tied;

      const Point& q = to.positions[j];
      const double e[3] = {double(p[0] - q[0]), double(p[1] - q[1]), double(p[2] - q[2])};
      const double d1 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
      sum.d1_mse += d1;
      sum.d1_hausdorff = std::max(sum.d1_hausdorff, d1);
      if (to_normals) {
        double d2 = 0;
        if (options.average_normals) {
          for (std::size_t k = 0; k < tied; ++k) {
            const Point& t = to.positions[s.index[k]];
            const Point& n = (*to_normals)[s.index[k]];
            if (!has_nan(n)) {
              const float along = (p[0] - t[0]) * n[0] + (p[1] - t[1]) * n[1] + (p[2] - t[2]) * n[2];
              d2 += double(along * along);
            } else {  // pc_error adds the coordinates' differences, unsquared, as it writes them
              d2 += double(p[0] - t[0] + p[1] - t[1] + p[2] - t[2]);
            }
          }
          d2 /= double(tied);
        } else {
          const Point& n = (*to_normals)[j];
          if (!has_nan(n)) {
            const double along = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
            d2 = along * along;
          } else {
            d2 = d1;
          }
        }
        sum.d2_mse += d2;
        sum.d2_hausdorff = std::max(sum.d2_hausdorff, d2);
      }
      if (colour) {
        const Colour& mine = from.colours[i];
        const Colour theirs = matched_colour(mine, to, s.index.data(), tied, j, options.neighbors_proc);
        const std::array<float, 3> in = pc_error_ycbcr(mine), out = pc_error_ycbcr(theirs);
        const std::array<float, 3> in8 = pc_error_ycocg(mine), out8 = pc_error_ycocg(theirs);
        for (int c = 0; c < 3; ++c) {
          const float dy = in[c] - out[c];
          sum.ycbcr_mse[c] += double(dy * dy);
          const float dc = float(mine[c]) - float(theirs[c]);
          sum.rgb_mse[c] += double(dc * dc);
          sum.rgb_hausdorff[c] = std::max(sum.rgb_hausdorff[c], double(dc * dc));
          if (figures.ycocg) {
            const float d8 = in8[c] - out8[c];
            sum.ycocg_mse[c] += double(d8 * d8);
          }
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

}  // namespace

void pc_error_directions(const MpegPoints& a, const MpegPoints& b, const std::vector<Point>* b_normals,
                         const PcErrorOptions& options, double threshold, MpegFigures& figures) {
  std::unique_ptr<Tree> a_tree, b_tree;
  tbb::parallel_invoke([&] { a_tree = std::make_unique<Tree>(a); }, [&] { b_tree = std::make_unique<Tree>(b); });
  std::vector<Point> carried;
  if (figures.d2 && !b_normals) {
    carried = carried_normals(a, *a_tree, b, *b_tree, options.average_normals);
    b_normals = &carried;
  }
  figures.a_to_b = direction(a, b, *b_tree, figures.d2 ? b_normals : nullptr, options, threshold, figures);
  figures.b_to_a = direction(b, a, *a_tree, figures.d2 ? &a.normals : nullptr, options, threshold, figures);
}

}  // namespace roving
