// Which pixels of a viewpoint-sampling view its samples read, and which triangles of M_C can
// cover them. A view then draws only those triangles, scissored to the rectangle around the
// read pixels (DepthRenderer::render_view_part): every pixel read keeps the depth the whole
// view gives it, while a view's ~240 samples read about 1% of its image.
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/gl/depth_renderer.h"
#include "roving/gl_methods/triangle_clusters.h"

namespace roving {

class ViewFootprint {
 public:
  // The pixels that reading `samples[group]` may touch: around each sample's normal-line segment
  // [x - reach n, x + reach n] as the view projects it (reach = h when the line is marched
  // across the view, 0 when the view is read at the sample), with the 4 x 4 neighbourhood the
  // reading inspects.
  ViewFootprint(const OrthoCamera& camera, int resolution, const SampleSet& samples,
                const std::vector<std::uint32_t>& group, double reach);

  // The pixels' bounding rectangle, within the image.
  const PixelRect& rect() const { return rect_; }
  // Whether some sample may read pixel (i, j).
  bool covers(int i, int j) const;
  // Rectangles within rect() holding every pixel some sample may read: the 8 x 8-pixel squares
  // that hold one, consecutive squares of a row merged.
  std::vector<PixelRect> read_squares() const;

  // The corners (three a triangle) of the triangles of the mesh `clusters` were made from that
  // can cover a pixel some sample reads (its centre within a quarter pixel of the projected
  // triangle): the only ones that can set its depth.
  std::vector<std::uint32_t> corners_reaching(const TriangleClusters& clusters) const;

 private:
  // One bit per square of 2^shift x 2^shift pixels, row by row. Pixel ranges are inclusive,
  // not empty, and already clamped to the image.
  class Bitmap {
   public:
    Bitmap(int resolution, int shift);
    void mark(int i0, int j0, int i1, int j1);
    bool any(int i0, int j0, int i1, int j1) const;
    // Whether test(i, j) holds for some marked square (i, j) of the range, in row order.
    template <class Test>
    bool any_where(int i0, int j0, int i1, int j1, const Test& test) const;
    // The marked squares as runs [i0, i1) x [j, j + 1) along each row (in squares).
    std::vector<PixelRect> runs() const;

   private:
    int shift_, side_, words_;  // side_ squares a row, in words_ 64-bit words
    std::vector<std::uint64_t> bits_;
  };

  // Marks pixels [i0, i1] x [j0, j1] (inclusive, clamped to the image).
  void mark(int i0, int j0, int i1, int j1);
  // Whether any pixel in [i0, i1] x [j0, j1] (inclusive, clamped) is marked: the coarse bitmap
  // rejects most ranges in a word or two, the fine one decides the rest.
  bool any_marked(int i0, int j0, int i1, int j1) const;

  static constexpr int kCoarseShift = 3;  // coarse squares of 8 x 8 pixels

  OrthoCamera camera_;
  int resolution_;
  Bitmap fine_, coarse_;  // pixels read; squares holding one
  PixelRect rect_;
};

}  // namespace roving
