// Pictures of a value on a reference's surface (the heat map's signed distance, or a category
// such as how the cooperative method resolved each sample): the surface coloured per element,
// rendered lit from the front, the side and the top by the GL renderer, with a title and a
// legend, written as PNG by cairo.
#pragma once

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/formats/outputs/heatmap.h"
#include "roving/gl/shaded_renderer.h"

namespace roving {

struct PictureLegend {
  // A diverging colour bar of d over [-range, range], labelled in model units and in % of
  // `diagonal`; or, for the colour difference, a sequential bar of delta E over [0, range].
  HeatmapQuantity quantity = HeatmapQuantity::Distance;
  double range = 0, diagonal = 0;
  // Or, when not empty, one swatch per category instead of the bar.
  std::vector<std::pair<Rgb, std::string>> categories;
  // The grey of elements without a value, as the legend names it; empty: not in the legend.
  std::string no_value_label = "no hit";
};

struct Picture {
  std::string title, subtitle;
  PictureLegend legend;
  int view_size = 400;  // pixels per side of each view
};

// The surface (or the samples, for Points or a null surface) with each element's colour.
ColouredSurface coloured_surface(const TriangleMesh* surface, const HeatmapLayout& layout,
                                 const SampleSet& samples, const std::vector<Rgb>& element_colours);

// The heat map's colours for heatmap_values() on `scale`, no-hit grey for NaN.
std::vector<Rgb> heatmap_colours(const std::vector<float>& values, const HeatmapScale& scale);

// Renders `surface` seen from +z (front), +x (side) and +y (top) and writes the picture as PNG.
// Throws roving::Error when GL or cairo fails.
void write_picture_png(std::FILE* out, GlBackend backend, const ColouredSurface& surface,
                       const Picture& picture);

}  // namespace roving
