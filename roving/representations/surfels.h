// Point clouds as test models (beyond the paper, which rules them out at the end of its Section
// 4.3): each point drawn as an oriented disk (a surfel) in its tangent plane, as a small fan of
// triangles, so the depth pass, Embree and CGAL all see the same surface.
#pragma once

#include <string>

#include "roving/core/point_cloud.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// The radius rule. A point's disk reaches its k-th nearest neighbour: for points spread
// uniformly at random over a surface with density rho, the chance that a spot is covered by no
// disk is about exp(-rho * pi * r^2) = exp(-k) (0.03% at k = 8). The price is the bias: along a
// normal line the first hit is the outermost of the overlapping disks, on a convex surface of
// curvature kappa a rim about kappa * r^2 / 2 above it.
struct SurfelRule {
  int neighbours = 8;  // k
  int fan_sides = 8;   // each disk a regular polygon of this many triangles around its point,
                       // circumscribing the disk so that it covers all of it
};

struct SurfelSurface {
  TriangleMesh mesh;  // fan_sides triangles per point, point k's fan at triangles [k * sides, ...)
  SurfelRule rule;
  double min_radius = 0, median_radius = 0, max_radius = 0;
};

// Makes the surfels of `cloud` (positions with unit normals). Throws roving::Error naming `path`
// for no more than k points, a non-finite coordinate, a zero or non-finite normal, or two points
// at the same position (their disks would coincide and the radius rule would read 0).
SurfelSurface make_surfels(const PointCloud& cloud, const std::string& path, const SurfelRule& rule = {});

}  // namespace roving
