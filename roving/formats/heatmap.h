// The signed distance on the reference, as a PLY that MeshLab and CloudCompare open coloured:
// the reference's own triangles with a colour and a `quality` per face (face samples) or per
// vertex (vertex samples), or the samples as points where no element carries one sample.
#pragma once

#include <array>
#include <cstdio>
#include <optional>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"

namespace roving {

// ColorBrewer's diverging RdBu, reversed: blue (-1, TEST inside REF), near-white (0), red (+1);
// `s` clamped to [-1, 1].
std::array<unsigned char, 3> diverging_colour(double s);
// What a sample without a hit is drawn in: mid grey, apart from every colour of the map.
constexpr std::array<unsigned char, 3> kNoHitColour = {128, 128, 128};

// Where each sample's value goes: element `elements[k]` of the surface's faces or vertices (or
// both triangles of a voxel face: `per_element` triangles each).
enum class HeatmapElement { Faces, Vertices, Points };
struct HeatmapLayout {
  HeatmapElement element = HeatmapElement::Points;
  int triangles_per_element = 1;  // faces: 2 for a voxel's exposed face
};

// One value per element of the surface (faces or vertices as `layout` says; samples for
// Points or a null surface): its sample's `per_sample` value, NaN where no sample lands.
std::vector<float> heatmap_values(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                                  const std::vector<float>& per_sample);
// The colour map's default half-range: the 99th percentile of |d| over the hits, so the
// colours show the data rather than h; `fallback` when nothing hit or all of it is 0.
double default_heatmap_range(const DistanceResult& result, double fallback);
// d where a sample hit, NaN where it did not.
std::vector<float> distances_or_nan(const DistanceResult& result);

// Writes the heat map over [-range, range] (range > 0). `surface` may be null for points. The
// header's comments give the legend; a no-hit has NaN quality and kNoHitColour, an element
// without a sample (a zero-area face) NaN and no-hit grey too.
void write_heatmap_ply(std::FILE* out, const TriangleMesh* surface, const HeatmapLayout& layout,
                       const SampleSet& samples, const DistanceResult& result, double range);

}  // namespace roving
