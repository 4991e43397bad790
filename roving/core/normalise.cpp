// Normalisation to the paper's units.
#include "roving/core/normalise.h"

namespace roving {

Normalisation normalisation_of(const TriangleMesh& reference, double longest_side) {
  const BoundingBox& box = reference.bounding_box();
  return {box.min, longest_side / box.size().maxCoeff()};
}

}  // namespace roving
