// pc_error's loop as it is written (pcc_distortion.cpp's scaleNormals and findMetric, release
// 0.14.2), for the options under which a figure depends on which of several equally near points its
// k-d tree finds first or how many it looks at (--neighborsProc 0, 3, 4, --averageNormals 0,
// --dropdups 0 and 1, whose kept duplicates are such points), and for A's NaN normals, on which it
// computes on. Under pc_error's defaults point_cloud_psnr's faster search gives the same figures.
#pragma once

#include <vector>

#include "roving/mpeg/point_cloud_psnr.h"

namespace roving {

// A -> B and B -> A into `figures` (its d2, colour and ycocg say what to compute). A -> B's D2 is
// along `b_normals` where given (mmetric's B's own), else along A's normals carried onto B as
// scaleNormals carries them. Ties: consecutive squared distances within `threshold`.
void pc_error_directions(const MpegPoints& a, const MpegPoints& b, const std::vector<std::array<float, 3>>* b_normals,
                         const PcErrorOptions& options, double threshold, MpegFigures& figures);

}  // namespace roving
