// Internal: TEST's colour at the samples viewpoint-sampling views accept (the frame buffer beside
// the Z-buffer, paper Section 1). A view's sample is read between pixel centres, where no
// fragment was shaded, so a view draws beside its depth which triangle each pixel shows; the
// crossing is placed on the one shown around it that holds it, and M_C is shaded there by GL as
// a one-pixel tile (deferred shading): the cameras' shader and texture sampling, at the point.
#pragma once

#include <cstdint>
#include <vector>

#include "gl_passes.h"

namespace roving {

// The triangle of M_C under `point` in a view: of the triangles `triangles` (render_view's
// image: 1 + the index into `faces`, or into M_C's triangles where `faces` is empty) shows at
// the 2 x 2 pixel centres around the point's projection, the one nearest it across the view (0
// where it holds the point), the lowest index among equals. Requires a drawn pixel among them.
std::uint32_t face_under(const TriangleMesh& test, const OrthoCamera& camera, int resolution,
                         const std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& faces,
                         const Vec3& point);

// A sample a view accepted and where its colour is to be shaded: the point of M_C's triangle
// `face` nearest `point`.
struct ViewHit {
  std::uint32_t sample, face;
  Vec3 point;
};

// Shades every hit, as one-pixel tiles drawn in batches, and hands each sample's colour to
// `coloured`. Runs on the thread that holds the GL context; needs scene.prepare_colour().
void shade_view_hits(GlScene& scene, const std::vector<ViewHit>& hits, const Coloured& coloured);

}  // namespace roving
