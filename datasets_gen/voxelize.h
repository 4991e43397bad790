// Conservative surface voxelisation: every voxel whose closed cube meets a triangle.
#pragma once

#include "roving/core/triangle_mesh.h"
#include "roving/core/voxel_grid.h"

namespace roving {

// A dimension^3 grid over the cube on `mesh`'s bounding box (origin at its min corner, side its
// longest side); a voxel is occupied when a triangle meets its cube (exact triangle-box test,
// CGAL Epick), not when a sample point falls in it. Throws roving::Error for a dimension
// outside 1..1024.
VoxelGrid voxelize_conservative(const TriangleMesh& mesh, int dimension);

// Thin (26-separating) surface voxelisation (Huang, Yagel, Filippov and Kurzion 1998): of the
// voxels whose cube meets a triangle, those whose centre lies within (L / 2) max_i |n_i| of the
// triangle's plane (L the voxel side, n its unit normal), the thinnest set without holes a line of
// voxels could pass through. The paper's voxel models were thin ("thin discrete triangulation").
VoxelGrid voxelize_thin(const TriangleMesh& mesh, int dimension);

}  // namespace roving
