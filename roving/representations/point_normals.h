// Normals for point clouds that come without them.
#pragma once

#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

// PCA over the k nearest neighbours (CGAL::pca_estimate_normals), oriented consistently by a
// minimum spanning tree (CGAL::mst_orient_normals), then flipped as a whole if most normals
// point towards the centroid (outward for closed shapes). Throws roving::Error for fewer than
// k + 1 points.
std::vector<Vec3> estimate_normals(const std::vector<Vec3>& points, int k = 12);

}  // namespace roving
