// TEST's colour at viewpoint-sampling samples: the triangle under the crossing from the view's
// triangle image, then deferred shading as one-pixel tiles.
#include "view_colour.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "roving/core/geometry.h"

namespace roving {

std::uint32_t face_under(const TriangleMesh& test, const OrthoCamera& camera, int resolution,
                         const std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& faces,
                         const Vec3& point) {
  const Vec3 q = camera.to_normalised(point);
  const Vec3 at(q.x(), q.y(), 0);
  const double u = (0.5 * q.x() + 0.5) * resolution - 0.5, v = (0.5 * q.y() + 0.5) * resolution - 0.5;
  const int i0 = static_cast<int>(std::floor(u)), j0 = static_cast<int>(std::floor(v));
  std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
  double best_distance = std::numeric_limits<double>::infinity();
  for (int j = std::max(j0, 0); j <= std::min(j0 + 1, resolution - 1); ++j) {
    for (int i = std::max(i0, 0); i <= std::min(i0 + 1, resolution - 1); ++i) {
      const std::uint32_t shown = triangles[static_cast<std::size_t>(j) * resolution + i];
      if (shown == 0) continue;
      const std::uint32_t face = faces.empty() ? shown - 1 : faces[shown - 1];
      Vec3 corner[3];
      for (int c = 0; c < 3; ++c) {
        const Vec3 p = camera.to_normalised(test.positions()[test.triangles()[face][c]]);
        corner[c] = Vec3(p.x(), p.y(), 0);
      }
      const double distance = (closest_on_triangle(at, corner[0], corner[1], corner[2]).point - at).norm();
      if (distance < best_distance || (distance == best_distance && face < best)) {
        best = face, best_distance = distance;
      }
    }
  }
  return best;
}

void shade_view_hits(GlScene& scene, const std::vector<ViewHit>& hits, const Coloured& coloured) {
  // Each hit a tile covered by one quad of its shade, at the tile's middle depth; batches of
  // tiles in runs of one material, as the cameras draw them.
  constexpr std::size_t kTilesPerBatch = 64 * 64;
  std::vector<std::uint32_t> order(hits.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return scene.shades.material_of(hits[a].face) < scene.shades.material_of(hits[b].face);
  });
  std::vector<TileVertex> vertices;
  std::vector<TileShade> shades;
  std::vector<MaterialRun> runs;
  std::vector<float> depth;
  std::vector<Colour> colour;
  for (std::size_t first = 0; first < order.size(); first += kTilesPerBatch) {
    const std::size_t count = std::min(kTilesPerBatch, order.size() - first);
    vertices.clear(), shades.clear(), runs.clear();
    for (std::size_t tile = 0; tile < count; ++tile) {
      const ViewHit& hit = hits[order[first + tile]];
      const std::uint32_t material = scene.shades.material_of(hit.face);
      if (runs.empty() || runs.back().material != material) runs.push_back({material, 0});
      runs.back().vertex_count += 6;
      const TileShade shade = scene.shades.at(*scene.test, hit.face, hit.point);
      const auto t = static_cast<std::uint32_t>(tile);
      for (const auto& [x, y] : {std::pair(-1.0f, -1.0f),
                                 {1.0f, -1.0f},
                                 {1.0f, 1.0f},
                                 {-1.0f, -1.0f},
                                 {1.0f, 1.0f},
                                 {-1.0f, 1.0f}}) {
        vertices.push_back({x, y, 0.5f, t});
        shades.push_back(shade);
      }
    }
    scene.renderer->render_coloured_tiles(vertices, shades, runs, count, depth, colour);
    for (std::size_t tile = 0; tile < count; ++tile) coloured(hits[order[first + tile]].sample, colour[tile]);
  }
}

}  // namespace roving
