// Display surfaces: the heat map's elements as arrays a web page uploads, decimated by vertex
// clustering (Rossignac and Borrel 1993) when too large: one pass per grid size, coarsening the
// grid until the merged triangles fit the budget.
#include "roving/html/display_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace roving {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Which sample each element of the layout shows (as heatmap_values() places their values).
std::vector<std::int32_t> element_samples(const TriangleMesh& surface, const HeatmapLayout& layout,
                                          const SampleSet& samples) {
  const bool faces = layout.element == HeatmapElement::Faces;
  const std::size_t per = faces ? static_cast<std::size_t>(layout.triangles_per_element) : 1;
  std::vector<std::int32_t> sample(faces ? surface.triangle_count() : surface.vertex_count(), kNoSample);
  for (std::size_t k = 0; k < samples.size() && k < samples.elements.size(); ++k) {
    for (std::size_t j = 0; j < per; ++j) {
      const std::size_t e = samples.elements[k] * per + j;
      if (e < sample.size()) sample[e] = static_cast<std::int32_t>(k);
    }
  }
  return sample;
}

// A mean of values some of which are NaN: NaN where NaN has more than half the weight.
struct MeanOfValues {
  double sum = 0, weight = 0, nan_weight = 0;
  void add(float value, double w) {
    if (std::isnan(value)) {
      nan_weight += w;
    } else {
      sum += w * value, weight += w;
    }
  }
  float mean() const { return weight > 0 && nan_weight <= weight ? static_cast<float>(sum / weight) : kNaN; }
};

struct TripleHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& t) const {
    return (std::size_t(t[0]) * 73856093u) ^ (std::size_t(t[1]) * 19349663u) ^ (std::size_t(t[2]) * 83492791u);
  }
};

// The surface with its vertices merged per cell of a g^3 grid over its box.
DisplaySurface cluster(const TriangleMesh& surface, HeatmapElement element, const std::vector<float>& value,
                       int g) {
  const BoundingBox& box = surface.bounding_box();
  const Vec3 size = box.size().cwiseMax(Vec3::Constant(1e-30));
  std::unordered_map<std::uint64_t, std::uint32_t> cell_cluster;
  std::vector<std::uint32_t> cluster_of(surface.vertex_count(), 0);
  std::vector<Vec3> position_sum;
  std::vector<double> members;
  std::vector<MeanOfValues> vertex_value;
  for (std::size_t v = 0; v < surface.vertex_count(); ++v) {
    if (!surface.vertex_referenced()[v]) continue;
    const Vec3 cell = ((surface.positions()[v] - box.min).cwiseQuotient(size) * g).array().floor();
    const auto index = [&](int axis) { return static_cast<std::uint64_t>(std::clamp(int(cell[axis]), 0, g - 1)); };
    const std::uint64_t key = index(0) + std::uint64_t(g) * (index(1) + std::uint64_t(g) * index(2));
    const auto [it, added] = cell_cluster.emplace(key, static_cast<std::uint32_t>(position_sum.size()));
    if (added) position_sum.emplace_back(Vec3::Zero()), members.push_back(0), vertex_value.emplace_back();
    cluster_of[v] = it->second;
    position_sum[it->second] += surface.positions()[v];
    members[it->second] += 1;
    if (element == HeatmapElement::Vertices) vertex_value[it->second].add(value[v], 1);
  }
  DisplaySurface out;
  out.element = element;
  std::unordered_map<std::array<std::uint32_t, 3>, std::uint32_t, TripleHash> merged;
  std::vector<MeanOfValues> face_value;
  for (std::size_t f = 0; f < surface.triangle_count(); ++f) {
    const Triangle& t = surface.triangles()[f];
    const std::array<std::uint32_t, 3> c = {cluster_of[t[0]], cluster_of[t[1]], cluster_of[t[2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;  // collapsed
    std::array<std::uint32_t, 3> key = c;
    std::sort(key.begin(), key.end());
    const auto [it, added] = merged.emplace(key, static_cast<std::uint32_t>(face_value.size()));
    if (added) {  // the first face's winding
      out.triangles.insert(out.triangles.end(), c.begin(), c.end());
      face_value.emplace_back();
    }
    if (element == HeatmapElement::Faces) face_value[it->second].add(value[f], std::max(surface.face_area(f), 1e-300));
  }
  for (std::size_t i = 0; i < position_sum.size(); ++i) {
    const Vec3 p = position_sum[i] / members[i];
    out.positions.insert(out.positions.end(), {float(p.x()), float(p.y()), float(p.z())});
  }
  const std::vector<MeanOfValues>& means = element == HeatmapElement::Faces ? face_value : vertex_value;
  for (const MeanOfValues& m : means) out.values.push_back(m.mean());
  out.samples.assign(out.values.size(), kMerged);
  return out;
}

}  // namespace

DisplaySurface display_surface(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                               const std::vector<float>& per_sample, std::size_t max_triangles) {
  max_triangles = std::max<std::size_t>(max_triangles, 1);
  if (!surface || layout.element == HeatmapElement::Points) {
    DisplaySurface out;
    out.source_elements = samples.size();
    const std::size_t stride = (samples.size() + max_triangles - 1) / max_triangles;
    double area = 0;
    for (std::size_t k = 0; k < samples.size(); k += std::max<std::size_t>(stride, 1)) {
      const Vec3& p = samples.positions[k];
      out.positions.insert(out.positions.end(), {float(p.x()), float(p.y()), float(p.z())});
      out.values.push_back(per_sample[k]);
      out.samples.push_back(static_cast<std::int32_t>(k));
    }
    for (double w : samples.weights) area += w;
    // Disks of the area each point shown stands for, a quarter wider so that neighbours overlap.
    if (area > 0 && !out.values.empty()) out.point_size = static_cast<float>(2.5 * std::sqrt(area / out.values.size() / M_PI));
    return out;
  }
  const std::vector<float> value = heatmap_values(surface, layout, samples, per_sample);
  DisplaySurface out;
  if (surface->triangle_count() <= max_triangles) {
    out.element = layout.element;
    for (const Vec3& p : surface->positions()) out.positions.insert(out.positions.end(), {float(p.x()), float(p.y()), float(p.z())});
    for (const Triangle& t : surface->triangles()) out.triangles.insert(out.triangles.end(), t.begin(), t.end());
    out.values = value;
    out.samples = element_samples(*surface, layout, samples);
  } else {
    // A merged surface has about two triangles per cell it passes through, and a surface of area A
    // passes through about 1.5 A / s^2 cells of side s: start there, coarsen while over budget.
    const double side = std::sqrt(3 * surface->total_area() / max_triangles);
    const double extent = surface->bounding_box().size().maxCoeff();
    for (double g = side > 0 ? extent / side : 1;; g *= 0.85) {
      out = cluster(*surface, layout.element, value, std::max(1, static_cast<int>(g)));
      if (out.triangles.size() / 3 <= max_triangles || g < 2) break;
    }
  }
  out.source_elements = value.size();
  out.source_triangles = surface->triangle_count();
  return out;
}

}  // namespace roving
