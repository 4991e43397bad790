// TEST's colour at the samples a GL pass resolved: the face by the exact rule near the pass's d,
// then deferred shading as one-pixel tiles.
#include "hit_colour.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "roving/core/geometry.h"
#include "roving/core/normal_line.h"

namespace roving {

SampleHit hit_face(const GlScene& scene, const SampleSet& samples, std::uint32_t k, double d,
                   double max_error, double window) {
  const TriangleMesh& test = *scene.test;
  const double tolerance = kNormalLineTolerance * test.bounding_box().diagonal();
  const Vec3& x = samples.positions[k];
  const Vec3& n = samples.normals[k];
  const NormalLine line(x, n, max_error, tolerance);
  CrossingChoice choice(Semantics::FirstHit, max_error);
  const Vec3 at = x + d * n;
  std::uint32_t nearest = 0;
  double nearest_distance = std::numeric_limits<double>::infinity();
  const double reach = window + tolerance;
  scene.grid->for_each_along(x + (d - reach) * n, x + (d + reach) * n, [&](std::uint32_t face) {
    const Triangle& t = test.triangles()[face];
    const Vec3& a = test.positions()[t[0]];
    const Vec3& b = test.positions()[t[1]];
    const Vec3& c = test.positions()[t[2]];
    const auto crossing = line.crossing(a, b, c);
    if (crossing && crossing->high >= d - window && crossing->low <= d + window)
      choice.consider(*crossing, face);
    const double distance = (closest_on_triangle(at, a, b, c).point - at).norm();
    if (distance < nearest_distance || (distance == nearest_distance && face < nearest)) {
      nearest = face, nearest_distance = distance;
    }
  });
  if (const auto chosen = choice.chosen_hit()) return {k, chosen->face, x + chosen->distance * n};
  return {k, nearest, at};
}

void shade_hits(GlScene& scene, const std::vector<SampleHit>& hits, const Coloured& coloured) {
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
      const SampleHit& hit = hits[order[first + tile]];
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
