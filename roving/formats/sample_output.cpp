// CSV and PLY per-sample outputs.
#include "roving/formats/sample_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "roving/core/error.h"

namespace roving {
namespace {

// Blue (-1) .. white (0) .. red (+1).
std::array<unsigned char, 3> diverging_colour(double s) {
  s = std::clamp(s, -1.0, 1.0);
  const auto fade = [](double v) { return static_cast<unsigned char>(std::lround(255 * (1 - v))); };
  if (s >= 0) return {255, fade(s), fade(s)};
  return {fade(-s), fade(-s), 255};
}

}  // namespace

void write_samples_csv(std::FILE* out, const SampleSet& samples, const DistanceResult& result,
                       const std::string& direction, bool header) {
  if (header) fmt::print(out, "x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by{}\n", direction.empty() ? "" : ",direction");
  const std::string last = direction.empty() ? "" : "," + direction;
  const auto resolved_by = [&](std::size_t k) -> const char* {
    if (!result.gl) return "";
    switch (result.gl->resolved_by[k]) {
      case Resolution::View: return "view";
      case Resolution::Camera: return "camera";
      case Resolution::Unresolved: return "no-hit";
    }
    return "";
  };
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Vec3& p = samples.positions[k];
    const Vec3& n = samples.normals[k];
    const std::string d = result.hit[k] ? fmt::format("{}", result.signed_distance[k]) : "";
    const std::string element = k < samples.elements.size() ? fmt::format("{}", samples.elements[k]) : "";
    fmt::print(out, "{},{},{},{},{},{},{},{},{},{},{}{}\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), d,
               result.hit[k] ? 1 : 0, element, samples.weights[k], resolved_by(k), last);
  }
}

void write_heatmap_ply(std::FILE* out, const SampleSet& samples, const DistanceResult& result, double range) {
  if (!(range > 0)) range = 1;
  fmt::print(out,
             "ply\nformat ascii 1.0\ncomment surface roving heat map of signed distance d\n"
             "comment legend: d = -{0} blue, 0 white, +{0} red; grey = no hit\n"
             "element vertex {1}\nproperty float x\nproperty float y\nproperty float z\n"
             "property float nx\nproperty float ny\nproperty float nz\n"
             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
             "property float quality\nend_header\n",
             range, samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Vec3& p = samples.positions[k];
    const Vec3& n = samples.normals[k];
    const bool hit = result.hit[k] != 0;
    const double d = hit ? result.signed_distance[k] : 0.0;
    const auto colour = hit ? diverging_colour(d / range) : std::array<unsigned char, 3>{128, 128, 128};
    fmt::print(out, "{} {} {} {} {} {} {} {} {} {}\n", float(p.x()), float(p.y()), float(p.z()), float(n.x()),
               float(n.y()), float(n.z()), colour[0], colour[1], colour[2], hit ? float(d) : 0.0f);
  }
}

}  // namespace roving
