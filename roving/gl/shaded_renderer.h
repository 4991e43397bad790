// Lit, coloured pictures of a surface: the heat maps' renderings, not measurements. Runs on the
// same OSMesa / EGL contexts as the depth renderer, in a context of its own.
#pragma once

#include <array>
#include <vector>

#include "roving/gl/depth_renderer.h"

namespace roving {

using Rgb = std::array<unsigned char, 3>;

// What to draw: triangles (three consecutive positions each) or points, each position with
// its own normal and colour (equal normals and colours on a triangle draw it flat).
struct ColouredSurface {
  std::vector<Vec3> positions, normals;
  std::vector<Rgb> colours;
  bool points = false;
};

struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // row by row from the top, 3 bytes per pixel
};

// Draws `surface` through each camera (whose half_width / half_height should match width /
// height) on white, lit from over the viewer's left shoulder on both sides of each face, and
// returns one width x height image per camera. Each is drawn at 3x3 the size and averaged down,
// so edges are smooth. Throws roving::Error when no context can be made or the size is too big.
std::vector<RgbImage> render_shaded(GlBackend backend, const ColouredSurface& surface,
                                    const std::vector<OrthoCamera>& cameras, int width, int height);

}  // namespace roving
