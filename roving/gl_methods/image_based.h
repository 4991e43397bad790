// An image-based comparison beside the sample-based one, so that our figures can be related to
// MPEG's: IBSM as MPEG's mmetric v1.1.7 computes it (`compare --mode ibsm`, ISO/IEC JTC 1/SC 29/
// WG 7's V-DMC common test conditions), with its conventions (docs/colour.md says which, and
// tests/ibsm holds its own figures on our pairs). Both models are drawn unlit, each pixel its
// surface colour (a texture alone where there is one, bilinear and clamped to the edge; else
// vertex colours), from `views` orthographic cameras on a Fibonacci sphere around the box of
// both, every camera at the box's centre plus r = 1.01 x half its diagonal along its direction,
// looking at the centre, its view that sphere's width and depth; back faces are culled; each
// pixel is sampled at its corner. Only the pixels both models cover are compared: colour as 8-bit
// code values (an 8-bit frame buffer), depth as a fraction of 3 r. Built on the Z-buffer renderer
// with the GL methods' shading.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "roving/core/triangle_mesh.h"
#include "roving/gl/depth_renderer.h"

namespace roving {

struct ImageBasedOptions {
  GlBackend backend = default_gl_backend();
  int views = 16;         // mmetric's default camera count
  int resolution = 2048;  // pixels a side, mmetric's default
  bool cull_back_faces = true;
};

struct ImageBasedResult {
  int views = 0, resolution = 0;
  std::size_t matched_pixels = 0;                // covered by both models, over every view
  std::size_t unmatched_pixels = 0;              // covered by one only
  double unmatched_percent = 0;                  // 100 unmatched / matched, as mmetric reports it
  bool colour = false;                           // both models have colour: the colour figures below exist
  std::array<double, 3> rgb_mse{}, ycbcr_mse{};  // per channel over the matched pixels, code values^2
  std::array<double, 3> psnr_rgb_channels{};     // R, G and B each, peak 255
  double psnr_rgb = 0;                           // of the three channels' mean MSE, peak 255
  double psnr_ycbcr_611 = 0;                     // of (6 MSE_Y + MSE_Cb + MSE_Cr) / 8
  std::array<double, 3> psnr_ycbcr{};
  // 10 log10(1 / MSE) of the depth difference as a fraction of 3 r (mmetric's GEO PSNR: its clip-
  // space depth over the far plane's |z|, scaled to a peak of 255).
  double depth_psnr = 0;
  double box_ratio = 0;  // 100 x TEST's box diagonal / REF's
  double seconds = 0;
};

// mmetric's camera directions: point i of n on the unit sphere, y = 1 - 2 i / (n - 1), at the
// golden angle times i around y.
std::vector<Vec3> fibonacci_directions(int count);

// Throws roving::Error on options out of range (views < 2, a resolution the GL context cannot
// draw) and when no GL context can be made. PSNRs are at most 99.99 dB, mmetric's figure for
// images that agree; NaN where no pixel is covered by both (mmetric prints 99.99 there too).
ImageBasedResult image_based_comparison(const TriangleMesh& reference, const TriangleMesh& test,
                                        const ImageBasedOptions& options);

}  // namespace roving
