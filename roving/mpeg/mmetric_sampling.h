// A mesh sampled into a point cloud as MPEG's mmetric (1.1, `compare --mode pcc`) samples it before
// handing both clouds to pc_error's computation, so that `roving measure A.obj B.obj --pcc` gives
// mmetric's figures for a mesh codec's pair:
// - the mesh is first put in mmetric's canonical order ("oriented" reordering): its distinct
//   vertices (position, colour) sorted, each triangle rotated to start at its smallest vertex, the
//   triangles sorted and repeated ones dropped;
// - every triangle (area >= DBL_EPSILON) gives its three corners and, where its area is 2 or more
//   (model units squared), its three edge midpoints, and again for each of its four halves: at
//   most two levels; each point carries the normal of the triangle that made it and the colour
//   interpolated there;
// - points equal in position, normal and colour are kept once, in the order made.
// Everything in single precision, as mmetric's glm arithmetic.
#pragma once

#include "roving/core/point_cloud.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// Throws roving::Error for a textured mesh (mmetric fetches texels with its own filter; not
// reproduced).
PointCloud mmetric_samples(const TriangleMesh& mesh, const std::string& name);

}  // namespace roving
