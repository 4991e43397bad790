// Which pixels of a viewpoint-sampling view its samples read, and which triangles of M_C can
// cover them. A view then draws only those triangles, scissored to the rectangle around the
// read pixels (DepthRenderer::render_view_part): every pixel read keeps the depth the whole
// view gives it, while a view's ~240 samples cover under a fifth of its image.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/gl/depth_renderer.h"
#include "roving/gl_methods/triangle_clusters.h"

namespace roving {

class ViewFootprint {
 public:
  static constexpr int kCell = 4;  // pixels per cell side

  // The pixels that reading `samples[group]` may touch: around each sample's normal-line segment
  // [x - reach n, x + reach n] as the view projects it (reach = h when the line is marched
  // across the view, 0 when the view is read at the sample), with the 4 x 4 neighbourhood the
  // reading inspects and a pixel to spare.
  ViewFootprint(const OrthoCamera& camera, int resolution, const SampleSet& samples,
                const std::vector<std::uint32_t>& group, double reach);

  // The pixels' bounding rectangle, whole cells, within the image.
  const PixelRect& rect() const { return rect_; }
  // Whether pixel (i, j) lies in a cell some sample reads.
  bool covers(int i, int j) const;

  // The triangles (of the mesh `clusters` were made from) whose projected bounding box (with a
  // pixel to spare) touches a cell some sample reads: the only ones that can set the depth of a
  // pixel read.
  std::vector<std::uint32_t> triangles_reaching(const TriangleClusters& clusters) const;

 private:
  // Whether any cell in [cx0, cx1] x [cy0, cy1] (inclusive, clamped) is read.
  bool any_cell(int cx0, int cy0, int cx1, int cy1) const;

  OrthoCamera camera_;
  int resolution_, cells_;
  std::vector<std::uint8_t> read_;     // per cell, row by row
  std::vector<std::uint32_t> summed_;  // summed-area table of read_, (cells + 1)^2
  PixelRect rect_;
};

}  // namespace roving
