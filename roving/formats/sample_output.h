// Per-sample outputs of a measurement: a CSV table and a colour-coded PLY "heat map".
#pragma once

#include <cstdio>
#include <string>
#include <string>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"

namespace roving {

// One row per sample: x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by. d is empty for a no-hit;
// element is the sample's face, vertex, patch, exposed face or point index; resolved_by says for
// GL methods whether a view or a per-sample camera answered (or no-hit), empty for the others.
// A non-empty `direction` ("A -> B") adds a last column naming it, so that both directions of a
// two-sided run share one table; `header` writes the column names first. Write errors are left
// on `out` for its owner (an AtomicFile) to report.
void write_samples_csv(std::FILE* out, const SampleSet& samples, const DistanceResult& result,
                       const std::string& direction = {}, bool header = true);

// The samples as a PLY point cloud with normals, coloured by signed d on a diverging map
// (blue: M_C inside M_R, white: 0, red: outside) over the symmetric legend range [-range, range];
// no-hits are grey. Each vertex also carries d as a scalar property (`quality`), read by
// MeshLab and CloudCompare; the legend range is written in a header comment.
void write_heatmap_ply(std::FILE* out, const SampleSet& samples, const DistanceResult& result, double range);

}  // namespace roving
