// CSV and PLY per-sample outputs.
#include "roving/formats/outputs/sample_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "roving/core/colour_science.h"
#include "roving/core/error.h"

namespace roving {

void write_samples_csv(std::FILE* out, const SampleSet& samples, const DistanceResult& result,
                       const std::string& direction, bool header, const ColourPairs* colours,
                       const Correspondences* correspondences) {
  if (header) {
    fmt::print(out, "x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by{}{}{}\n",
               colours ? ",ref_r,ref_g,ref_b,test_r,test_g,test_b,delta_e" : "",
               correspondences ? ",test_face,test_x,test_y,test_z,bary_0,bary_1,bary_2" : "",
               direction.empty() ? "" : ",direction");
  }
  const bool faces = result.hit_face.size() == samples.size();
  // A NaN coordinate (unknown) as an empty field.
  const auto triple = [](const Vec3& v) {
    return v.allFinite() ? fmt::format(",{},{},{}", v.x(), v.y(), v.z()) : std::string(",,,");
  };
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
    std::string colour;
    if (colours) {
      const Colour& ref = colours->reference[k];
      const Colour& test = colours->test[k];
      colour = fmt::format(",{},{},{}", ref.x(), ref.y(), ref.z());
      colour +=
          result.hit[k]
              ? fmt::format(",{},{},{},{}", test.x(), test.y(), test.z(),
                            ciede2000(srgb_to_lab(ref.cast<double>()), srgb_to_lab(test.cast<double>())))
              : ",,,,";
    }
    std::string on_test;
    if (correspondences) {
      on_test = faces && result.hit[k] ? fmt::format(",{}", result.hit_face[k]) : ",";
      on_test += triple(correspondences->points[k]) + triple(correspondences->barycentric[k]);
    }
    fmt::print(out, "{},{},{},{},{},{},{},{},{},{},{}{}{}{}\n", p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), d,
               result.hit[k] ? 1 : 0, element, samples.weights[k], resolved_by(k), colour, on_test, last);
  }
}

}  // namespace roving
