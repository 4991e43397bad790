// Shared edge points are made once per undirected edge (keyed by its two corners) and read
// in the edge's own direction, so neighbouring triangles weld.
#include "subdivide.h"

#include <fmt/format.h>

#include <unordered_map>

#include "roving/core/error.h"

namespace roving {

TriangleMesh split_triangles(const TriangleMesh& mesh, int n) {
  if (n < 1) throw Error(fmt::format("split_triangles: expected n >= 1, found {}", n));
  const auto& p = mesh.positions();
  std::vector<Vec3> positions = p.to_vector();
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.triangle_count() * n * n);
  // First of the n - 1 interior points of edge (a, b), a < b, running from a to b.
  std::unordered_map<std::uint64_t, int> edge_points;
  const auto edge_point = [&](int a, int b, int k) {  // point k of n along a -> b, 0 < k < n
    const bool forward = a < b;
    const int low = forward ? a : b, high = forward ? b : a;
    const std::uint64_t key = (std::uint64_t(low) << 32) | std::uint32_t(high);
    auto [it, inserted] = edge_points.try_emplace(key, static_cast<int>(positions.size()));
    if (inserted) {
      for (int j = 1; j < n; ++j) positions.push_back(p[low] + (p[high] - p[low]) * (double(j) / n));
    }
    return it->second + (forward ? k : n - k) - 1;
  };
  std::vector<int> grid;
  for (const Triangle& t : mesh.triangles()) {
    // Grid point (i, j), i + j <= n, at t0 + i/n (t1 - t0) + j/n (t2 - t0).
    grid.assign((n + 1) * (n + 1), -1);
    const auto at = [&](int i, int j) -> int& { return grid[i * (n + 1) + j]; };
    at(0, 0) = t[0], at(n, 0) = t[1], at(0, n) = t[2];
    for (int k = 1; k < n; ++k) {
      at(k, 0) = edge_point(t[0], t[1], k);
      at(n - k, k) = edge_point(t[1], t[2], k);
      at(0, n - k) = edge_point(t[2], t[0], k);
    }
    for (int i = 1; i < n; ++i) {
      for (int j = 1; i + j < n; ++j) {
        at(i, j) = static_cast<int>(positions.size());
        positions.push_back(p[t[0]] + (p[t[1]] - p[t[0]]) * (double(i) / n) + (p[t[2]] - p[t[0]]) * (double(j) / n));
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  return TriangleMesh(std::move(positions), std::move(triangles), fmt::format("split {}", n));
}

}  // namespace roving
