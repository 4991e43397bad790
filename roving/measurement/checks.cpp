// Checks behind the report's warnings.
#include "checks.h"

#include <fmt/format.h>

#include "roving/core/mesh_orientation.h"

namespace roving {

std::vector<std::string> alignment_warnings(const Model& reference, const Model& test, double max_error) {
  std::vector<std::string> warnings;
  const BoundingBox a = reference.bounding_box(), b = test.bounding_box();
  // Per axis, how far apart the boxes are (negative: they overlap there).
  const Vec3 gap = (a.min - b.max).cwiseMax(b.min - a.max);
  // How far the reference's box reaches out of the test's: samples out there can meet nothing
  // within h (a shift, a scale or a turn between frames). The other way round is no sign of a
  // mistake: a partial scan measured against the whole model.
  const double reach = (b.min - a.min).cwiseMax(a.max - b.max).cwiseMax(0.0).maxCoeff();
  if ((gap.array() > 0).any()) {
    warnings.push_back(fmt::format(
        "the bounding boxes of {} and {} do not overlap (gap {:.6g}; diagonals {:.6g} and {:.6g}): are they in "
        "the same frame and units?",
        reference.path(), test.path(), gap.cwiseMax(0.0).norm(), a.diagonal(), b.diagonal()));
  } else if (reach > max_error) {
    warnings.push_back(fmt::format(
        "the bounding box of {} reaches {:.6g} beyond that of {}, more than h = {:.6g} (diagonals {:.6g} and "
        "{:.6g}): are they aligned, in the same frame and units?",
        reference.path(), reach, test.path(), max_error, a.diagonal(), b.diagonal()));
  }
  return warnings;
}

std::vector<std::string> orientation_warnings(const Model& reference) {
  std::vector<std::string> warnings;
  if (reference.type != ModelType::Points) {
    const Orientation o = orientation(reference.mesh.mesh);
    if (o.closed_and_consistent && o.signed_volume < 0) {
      warnings.push_back(fmt::format(
          "{} is closed but inside out (signed volume {:.6g}): its normals point inward, so every signed d "
          "has the opposite sign; flip its winding",
          reference.path(), o.signed_volume));
    }
  }
  return warnings;
}

std::vector<std::string> result_warnings(const Statistics& s, Semantics semantics) {
  std::vector<std::string> warnings;
  if (s.no_hit_fraction > 0.05) {
    warnings.push_back(fmt::format(
        "{:.3g}% of the samples ({} of {}) found no surface within h{}", 100 * s.no_hit_fraction, s.no_hit_count,
        s.sample_count,
        semantics == Semantics::Closest ? "" : ": is h too small, or the models misaligned? --semantics closest "
                                               "always finds the nearest point"));
  }
  return warnings;
}

std::string no_colour_warning(const std::string& method) {
  return fmt::format(
      "colour: {} gives no colour (no face of TEST for each hit, no frame buffer); colour figures come from "
      "embree, cgal and the GL methods",
      method);
}

}  // namespace roving
