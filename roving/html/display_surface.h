// What a web page draws of a heat map: the reference's triangles (or its samples as points) with
// one value per element, reduced to a triangle budget by vertex clustering where the reference
// is larger, so that a page of a 10 M-triangle scan still opens.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"
#include "roving/formats/outputs/heatmap.h"

namespace roving {

// Per element: the sample it shows, or one of these.
constexpr std::int32_t kNoSample = -1;  // no sample lands on the element (a zero-area face)
constexpr std::int32_t kMerged = -2;    // a decimated element: the mean of the elements merged into it

struct DisplaySurface {
  HeatmapElement element = HeatmapElement::Points;  // what `values` are per: triangles, vertices or points
  std::vector<float> positions;                     // x y z per vertex (per point for Points)
  std::vector<std::uint32_t> triangles;             // 3 vertex indices per triangle; empty for Points
  std::vector<float> values;                        // per element; NaN: no value (a no-hit)
  std::vector<std::int32_t> samples;                // per element: its sample, kNoSample or kMerged
  float point_size = 0;                             // Points: a disk's diameter that covers the surface
  std::size_t source_elements = 0;                  // before decimation
  std::size_t source_triangles = 0;
  bool decimated() const { return values.size() < source_elements; }
};

// The heat map of `per_sample` values on `surface` (null: the samples as points), laid out as
// `layout` says (per triangle for Faces). Where the surface has more than `max_triangles`
// triangles (or the samples more than that many points), vertices are merged on a grid until it
// fits: a merged triangle shows the area-weighted mean of its faces' values (no value where most
// of its area has none), a merged vertex the mean of its vertices'; points are subsampled evenly.
DisplaySurface display_surface(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                               const std::vector<float>& per_sample, std::size_t max_triangles);

}  // namespace roving
