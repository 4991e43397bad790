// PLY heat maps: a binary-free ASCII PLY, so the legend comments and NaN read as text.
#include "roving/formats/outputs/heatmap.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace roving {

namespace {

// The colour at `position` (0 to N - 1) along N stops, interpolated linearly between neighbours.
template <std::size_t N>
std::array<unsigned char, 3> between_stops(const unsigned char (&stops)[N][3], double position) {
  const int low = std::min(static_cast<int>(position), static_cast<int>(N) - 2);
  const double t = position - low;
  std::array<unsigned char, 3> colour;
  for (int c = 0; c < 3; ++c) {
    colour[c] = static_cast<unsigned char>(std::lround((1 - t) * stops[low][c] + t * stops[low + 1][c]));
  }
  return colour;
}

}  // namespace

std::array<unsigned char, 3> diverging_colour(double s) {
  // RdBu, 11 classes, from blue to red (Brewer 2002).
  static constexpr unsigned char stops[11][3] = {{5, 48, 97},    {33, 102, 172}, {67, 147, 195}, {146, 197, 222},
                                                 {209, 229, 240}, {247, 247, 247}, {253, 219, 199}, {244, 165, 130},
                                                 {214, 96, 77},   {178, 24, 43},  {103, 0, 31}};
  return between_stops(stops, (std::clamp(std::isnan(s) ? 0.0 : s, -1.0, 1.0) + 1) * 5);  // 0..10
}

std::array<unsigned char, 3> sequential_colour(double s) {
  // YlOrRd, 9 classes (Brewer 2002).
  static constexpr unsigned char stops[9][3] = {{255, 255, 204}, {255, 237, 160}, {254, 217, 118},
                                                {254, 178, 76},  {253, 141, 60},  {252, 78, 42},
                                                {227, 26, 28},   {189, 0, 38},    {128, 0, 38}};
  return between_stops(stops, std::clamp(std::isnan(s) ? 0.0 : s, 0.0, 1.0) * 8);  // 0..8
}

std::array<unsigned char, 3> HeatmapScale::colour(float value) const {
  if (std::isnan(value)) return kNoHitColour;
  return quantity == HeatmapQuantity::Distance ? diverging_colour(value / range)
                                               : sequential_colour(value / range);
}

std::vector<float> heatmap_values(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                                  const std::vector<float>& per_sample) {
  if (!surface || layout.element == HeatmapElement::Points) return per_sample;
  const bool faces = layout.element == HeatmapElement::Faces;
  const std::size_t per = faces ? static_cast<std::size_t>(layout.triangles_per_element) : 1;
  std::vector<float> value(faces ? surface->triangle_count() : surface->vertex_count(),
                           std::numeric_limits<float>::quiet_NaN());
  for (std::size_t k = 0; k < samples.size() && k < samples.elements.size(); ++k) {
    for (std::size_t j = 0; j < per; ++j) {
      const std::size_t e = samples.elements[k] * per + j;
      if (e < value.size()) value[e] = per_sample[k];
    }
  }
  return value;
}

double default_heatmap_range(const DistanceResult& result, double fallback) {
  std::vector<float> magnitudes;
  for (std::size_t k = 0; k < result.hit.size(); ++k) {
    if (result.hit[k]) magnitudes.push_back(static_cast<float>(std::abs(result.signed_distance[k])));
  }
  return percentile_99(std::move(magnitudes), fallback);
}

double default_heatmap_range(StatisticsAccumulator& statistics, std::size_t hits, double fallback) {
  if (hits == 0) return fallback;
  const auto at = static_cast<float>(statistics.hit_magnitude(percentile_99_rank(hits)));
  return at > 0 ? at : fallback;
}

double percentile_99(std::vector<float> values, double fallback) {
  values.erase(std::remove_if(values.begin(), values.end(), [](float v) { return std::isnan(v); }),
               values.end());
  if (values.empty()) return fallback;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(percentile_99_rank(values.size()));
  std::nth_element(values.begin(), at, values.end());
  return *at > 0 ? *at : fallback;
}

std::size_t percentile_99_rank(std::size_t count) { return static_cast<std::size_t>(0.99 * (count - 1)); }

std::vector<float> distances_or_nan(const DistanceResult& result) {
  std::vector<float> d(result.hit.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (result.hit[k]) d[k] = static_cast<float>(result.signed_distance[k]);
  }
  return d;
}

void write_heatmap_ply(std::FILE* out, const TriangleMesh* surface, const HeatmapLayout& layout,
                       const SampleSet& samples, const std::vector<float>& per_sample,
                       const HeatmapScale& scale) {
  const HeatmapElement element = surface ? layout.element : HeatmapElement::Points;
  const std::vector<float> value = heatmap_values(surface, layout, samples, per_sample);
  const double range = scale.range;
  fmt::print(out, "ply\nformat ascii 1.0\n");
  const char* per = element == HeatmapElement::Faces      ? "per face"
                    : element == HeatmapElement::Vertices ? "per vertex"
                                                          : "per sample point";
  if (scale.quantity == HeatmapQuantity::Distance) {
    fmt::print(out,
               "comment surface roving heat map of signed distance d ({})\n"
               "comment legend: d = -{} blue (TEST inside REF), 0 white, +{} red (outside); grey = no hit "
               "(quality nan)\n",
               per, range, range);
  } else {
    fmt::print(
        out,
        "comment surface roving heat map of colour difference, CIEDE2000 delta E between REF's and "
        "TEST's colours ({})\n"
        "comment legend: delta E = 0 pale yellow (colours agree), {} dark red; grey = no hit, no colour "
        "(quality nan)\n",
        per, range);
  }
  const bool per_vertex = element != HeatmapElement::Faces;
  const std::size_t vertices = element == HeatmapElement::Points ? samples.size() : surface->vertex_count();
  fmt::print(out, "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n", vertices);
  if (element == HeatmapElement::Points) fmt::print(out, "property float nx\nproperty float ny\nproperty float nz\n");
  if (per_vertex) {
    fmt::print(out, "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n");
  }
  if (element != HeatmapElement::Points) {
    fmt::print(out, "element face {}\nproperty list uchar int vertex_indices\n", surface->triangle_count());
    if (!per_vertex) {
      fmt::print(out, "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n");
    }
  }
  fmt::print(out, "end_header\n");
  const auto coloured = [&](float v) {
    const auto c = scale.colour(v);
    return fmt::format("{} {} {} {}", c[0], c[1], c[2], v);  // fmt writes NaN as "nan"
  };
  if (element == HeatmapElement::Points) {
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const Vec3& p = samples.positions[k];
      const Vec3& n = samples.normals[k];
      fmt::print(out, "{} {} {} {} {} {} {}\n", float(p.x()), float(p.y()), float(p.z()), float(n.x()), float(n.y()),
                 float(n.z()), coloured(value[k]));
    }
    return;
  }
  for (std::size_t v = 0; v < surface->vertex_count(); ++v) {
    const Vec3& p = surface->positions()[v];
    fmt::print(out, "{} {} {}{}\n", float(p.x()), float(p.y()), float(p.z()),
               per_vertex ? " " + coloured(value[v]) : std::string());
  }
  for (std::size_t f = 0; f < surface->triangle_count(); ++f) {
    const Triangle& t = surface->triangles()[f];
    fmt::print(out, "3 {} {} {}{}\n", t[0], t[1], t[2], per_vertex ? std::string() : " " + coloured(value[f]));
  }
}

}  // namespace roving
