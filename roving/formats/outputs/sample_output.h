// Per-sample output of a measurement: a CSV table (the heat map is heatmap.h).
#pragma once

#include <cstdio>
#include <string>

#include "roving/core/colour.h"
#include "roving/core/correspondence.h"
#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"

namespace roving {

// One row per sample: x,y,z,nx,ny,nz,d,hit,element,weight,resolved_by. d is empty for a no-hit;
// element is the sample's face, vertex, patch, exposed face or point index; resolved_by says for
// GL methods whether a view or a per-sample camera answered (or no-hit), empty for the others.
// A non-empty `direction` ("A -> B") adds a last column naming it, so that both directions of a
// two-sided run share one table; `header` writes the column names first. Write errors are left
// on `out` for its owner (an AtomicFile) to report. With `colours`, columns ref_r, ref_g, ref_b,
// test_r, test_g, test_b (sRGB code values, 0-255) and delta_e (CIEDE2000) follow resolved_by;
// the test colour and delta_e are empty for a no-hit. With `correspondences`, columns test_face,
// test_x, test_y, test_z (the point on TEST) and bary_0, bary_1, bary_2 (its barycentric
// coordinates in test_face) follow, each empty where it is unknown (correspondence.h).
void write_samples_csv(std::FILE* out, const SampleSet& samples, const DistanceResult& result,
                       const std::string& direction = {}, bool header = true,
                       const ColourPairs* colours = nullptr, const Correspondences* correspondences = nullptr);

}  // namespace roving
