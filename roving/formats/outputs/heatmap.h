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
#include "roving/core/statistics.h"

namespace roving {

// ColorBrewer's diverging RdBu, reversed: blue (-1, TEST inside REF), near-white (0), red (+1);
// `s` clamped to [-1, 1].
std::array<unsigned char, 3> diverging_colour(double s);
// ColorBrewer's sequential YlOrRd: pale yellow (0, colours agree) to dark red (1); `s` clamped to
// [0, 1].
std::array<unsigned char, 3> sequential_colour(double s);
// What a sample without a hit is drawn in: mid grey, apart from every colour of the map.
constexpr std::array<unsigned char, 3> kNoHitColour = {128, 128, 128};

// What a heat map shows: the signed distance d on the diverging map over [-range, range], or the
// colour difference (CIEDE2000 delta E between REF's and TEST's colours) on the sequential map
// over [0, range].
enum class HeatmapQuantity { Distance, DeltaE };
struct HeatmapScale {
  HeatmapQuantity quantity = HeatmapQuantity::Distance;
  double range = 1;  // > 0
  // The map's colour of `value`; no-hit grey for NaN (no hit, or no colour to compare).
  std::array<unsigned char, 3> colour(float value) const;
};

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
// The same figure from the |d| an accumulator keeps for the percentiles (`hits` of its samples hit),
// for callers that fold samples in rather than hold them; call after its finish().
double default_heatmap_range(StatisticsAccumulator& statistics, std::size_t hits, double fallback);
// The 99th percentile of the values that are not NaN; `fallback` where there is none or it is 0.
double percentile_99(std::vector<float> values, double fallback);
// The rank (from 0) percentile_99 takes among `count` values (count > 0).
std::size_t percentile_99_rank(std::size_t count);
// d where a sample hit, NaN where it did not.
std::vector<float> distances_or_nan(const DistanceResult& result);

// Writes the heat map of `per_sample` values (d, or delta E; NaN where there is none) on `scale`.
// `surface` may be null for points. The header's comments give the legend; a sample without a
// value has NaN quality and kNoHitColour, an element without a sample (a zero-area face) NaN and
// no-hit grey too.
void write_heatmap_ply(std::FILE* out, const TriangleMesh* surface, const HeatmapLayout& layout,
                       const SampleSet& samples, const std::vector<float>& per_sample,
                       const HeatmapScale& scale);

}  // namespace roving
