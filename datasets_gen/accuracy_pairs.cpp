// Test models of every kind for the accuracy matrix.
#include "accuracy_pairs.h"

#include "analytic.h"
#include "decimate.h"
#include "roving/representations/voxel_surface.h"
#include "voxelize.h"

namespace roving {

std::vector<TestVariant> accuracy_variants(const TriangleMesh& reference) {
  // Even counts: a closed mesh loses triangles two at a time.
  const auto fraction = [&](double f) {
    return static_cast<std::size_t>(f * reference.triangle_count()) & ~std::size_t{1};
  };
  const double diagonal = reference.bounding_box().diagonal();
  std::vector<TestVariant> variants;
  variants.push_back({"decimated to 25%", decimate_quadric(reference, fraction(0.25))});
  variants.push_back({"decimated to 5%", decimate_quadric(reference, fraction(0.05))});
  variants.push_back({"perturbed 1%", smoothly_perturbed(reference, 0.01 * diagonal, 0.25 * diagonal)});
  variants.push_back({"voxelised 64", exposed_faces(voxelize_thin(reference, 64))});
  return variants;
}

}  // namespace roving
