// Per-sample outputs of a measurement: a CSV table and a colour-coded PLY "heat map".
#pragma once

#include <cstdio>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"

namespace roving {

// One row per sample: x,y,z,nx,ny,nz,d,hit (d empty for a no-hit). Write errors are left on
// `out` for its owner (an AtomicFile) to report.
void write_samples_csv(std::FILE* out, const SampleSet& samples, const DistanceResult& result);

// The samples as a PLY point cloud with normals, coloured by signed d on a diverging map
// (blue: M_C inside M_R, white: 0, red: outside) over the symmetric legend range [-range, range];
// no-hits are grey. Each vertex also carries d as a scalar property (`quality`), read by
// MeshLab and CloudCompare; the legend range is written in a header comment.
void write_heatmap_ply(std::FILE* out, const SampleSet& samples, const DistanceResult& result, double range);

}  // namespace roving
