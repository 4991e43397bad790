// Voxel models as surfaces (paper Section 4.3): their exposed faces as a test surface, and
// reference samples on those faces with axis normals.
#pragma once

#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"
#include "roving/core/voxel_grid.h"

namespace roving {

// The faces between an occupied and an empty voxel (or the grid's outside), two triangles each,
// facing out of the occupied voxel, on shared lattice vertices (watertight).
TriangleMesh exposed_faces(const VoxelGrid& grid);

// One sample per exposed face: its centre, its axis normal, its area as weight.
SampleSet exposed_face_samples(const VoxelGrid& grid);

}  // namespace roving
