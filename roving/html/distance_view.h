// One heat map of d for a page: the display surface, the per-sample resolution, the sign counts,
// the histogram and the main figures, from a method's result on a set of samples.
#pragma once

#include "roving/core/distance_method.h"
#include "roving/core/statistics.h"
#include "roving/html/html_page.h"

namespace roving {

// `surface` null: the samples as points. `range`: the colour map's half-range; `diagonal`: what %
// figures are of; `max_error`: h.
HtmlView distance_view(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                       const DistanceResult& result, const Statistics& statistics, double range, double diagonal,
                       double max_error);

}  // namespace roving
