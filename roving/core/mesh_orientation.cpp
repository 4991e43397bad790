// Closedness by cancellation: each directed edge a->b adds g(a, b) = f(a, b) - f(b, a) for a
// mixing hash f, so matched pairs cancel exactly (in wrapping 64-bit arithmetic) and a boundary
// or a flipped neighbour leaves a sum that is zero only with probability 2^-64. One pass, no
// edge map: the check costs as little as the volume beside it.
#include "roving/core/mesh_orientation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace roving {
namespace {

// splitmix64's finaliser over the ordered pair.
std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t z = a * 0x9E3779B97F4A7C15ull + b + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

Orientation orientation(const TriangleMesh& mesh) {
  // Volumes relative to the box centre: the same total for a closed mesh, with less cancellation.
  const Vec3 origin = mesh.bounding_box().centre();
  const auto& p = mesh.positions();
  const auto& triangles = mesh.triangles();
  // On all cores, in fixed blocks added in order, so that the volume does not depend on threads.
  constexpr std::size_t kBlock = 4096;
  const std::size_t blocks = (triangles.size() + kBlock - 1) / kBlock;
  std::vector<std::uint64_t> block_edges(blocks, 0);
  std::vector<double> block_volume6(blocks, 0.0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t block) {
    for (std::size_t f = block * kBlock; f < std::min(triangles.size(), (block + 1) * kBlock); ++f) {
      const Triangle& t = triangles[f];
      for (int e = 0; e < 3; ++e) {
        const std::uint64_t a = static_cast<std::uint32_t>(t[e]),
                            b = static_cast<std::uint32_t>(t[(e + 1) % 3]);
        block_edges[block] += mix(a, b) - mix(b, a);
      }
      block_volume6[block] += (p[t[0]] - origin).dot((p[t[1]] - origin).cross(p[t[2]] - origin));
    }
  });
  std::uint64_t edges = 0;
  double volume6 = 0;
  for (std::size_t block = 0; block < blocks; ++block)
    edges += block_edges[block], volume6 += block_volume6[block];
  return {mesh.triangle_count() > 0 && edges == 0, volume6 / 6};
}

}  // namespace roving
