// The toolbox's distance colours (distance_cloud_writer.h), each step as matplotlib and Open3D
// compute it, in double precision and their order of operations.
#include "roving/formats/outputs/distance_cloud_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace roving {
namespace {

constexpr int kEntries = 256;  // a matplotlib colour map's N

// One channel's segments (x, value below x, value above x), matplotlib's segmentdata.
using Segments = std::vector<std::array<double, 3>>;

// matplotlib's "hot" (_cm.py's _hot_data), per channel.
const std::array<Segments, 3> kHot = {
    Segments{{0.0, 0.0416, 0.0416}, {0.365079, 1.0, 1.0}, {1.0, 1.0, 1.0}},
    Segments{{0.0, 0.0, 0.0}, {0.365079, 0.0, 0.0}, {0.746032, 1.0, 1.0}, {1.0, 1.0, 1.0}},
    Segments{{0.0, 0.0, 0.0}, {0.746032, 0.0, 0.0}, {1.0, 1.0, 1.0}}};

// LinearSegmentedColormap.reversed(): (1 - x, above, below), last segment first.
Segments reversed(const Segments& segments) {
  Segments r;
  for (auto s = segments.rbegin(); s != segments.rend(); ++s) r.push_back({1.0 - (*s)[0], (*s)[2], (*s)[1]});
  return r;
}

// colors._create_lookup_table(N, segments) with gamma 1: the entries at np.linspace(0, 1, N),
// interpolated between the segments around each, clipped to [0, 1].
std::array<double, kEntries> lookup_table(const Segments& segments) {
  std::vector<double> x;
  for (const auto& s : segments) x.push_back(s[0] * (kEntries - 1));
  const double step = 1.0 / (kEntries - 1);  // np.linspace: k * step, the last exactly 1
  std::array<double, kEntries> table{};
  table.front() = segments.front()[2];
  table.back() = segments.back()[1];
  for (int k = 1; k + 1 < kEntries; ++k) {
    const double at = (kEntries - 1) * (k * step);
    const std::size_t i = std::size_t(std::lower_bound(x.begin(), x.end(), at) - x.begin());  // np.searchsorted
    const double distance = (at - x[i - 1]) / (x[i] - x[i - 1]);
    table[std::size_t(k)] = distance * (segments[i][1] - segments[i - 1][2]) + segments[i - 1][2];
  }
  for (double& v : table) v = std::clamp(v, 0.0, 1.0);
  return table;
}

}  // namespace

std::array<std::uint8_t, 3> hot_r_colour(double t) {
  static const std::array<std::array<double, kEntries>, 3> tables = {
      lookup_table(reversed(kHot[0])), lookup_table(reversed(kHot[1])), lookup_table(reversed(kHot[2]))};
  // Colormap.__call__ on floats: t * N, N itself taken as the last entry, truncated to an index.
  double scaled = t * kEntries;
  if (scaled == kEntries) scaled = kEntries - 1;
  const std::size_t entry = std::size_t(std::clamp(scaled, 0.0, double(kEntries - 1)));
  std::array<std::uint8_t, 3> colour;
  for (int c = 0; c < 3; ++c) {
    // Open3D's PLY writer: the value clamped to [0, 1], times 255, rounded (the toolbox's files agree).
    colour[std::size_t(c)] = std::uint8_t(std::round(std::clamp(tables[std::size_t(c)][entry], 0.0, 1.0) * 255.0));
  }
  return colour;
}

void write_distance_cloud_ply(std::FILE* out, const std::vector<Vec3>& points, const std::vector<double>& distances,
                              double max_distance) {
  const std::string header = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment roving: hot_r of min(d, {:.17g}) / {:.17g}, as the Tanks and "
      "Temples toolbox colours it\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
      max_distance, max_distance, points.size());
  std::fwrite(header.data(), 1, header.size(), out);
  char record[3 * 8 + 3];
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::memcpy(record, points[i].data(), 3 * 8);  // little-endian hosts (x86-64, arm64 Linux)
    const std::array<std::uint8_t, 3> colour = hot_r_colour(std::min(distances[i], max_distance) / max_distance);
    std::memcpy(record + 24, colour.data(), 3);
    std::fwrite(record, 1, sizeof record, out);
  }
}

}  // namespace roving
