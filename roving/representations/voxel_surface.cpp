// Voxel models as surfaces (paper Section 4.3): exposed faces and face samples.
#include "roving/representations/voxel_surface.h"

#include <array>
#include <unordered_map>

namespace roving {
namespace {

// The 6 face directions: axis, sign.
constexpr int kAxis[6] = {0, 0, 1, 1, 2, 2};
constexpr int kSign[6] = {1, -1, 1, -1, 1, -1};

// Calls visit(x, y, z, face) for every exposed face of the grid.
template <class Visit>
void for_each_exposed_face(const VoxelGrid& grid, Visit&& visit) {
  const int n = grid.dimension;
  for (int x = 0; x < n; ++x)
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y) {
        if (!grid.occupied[grid.index(x, y, z)]) continue;
        for (int face = 0; face < 6; ++face) {
          int neighbour[3] = {x, y, z};
          neighbour[kAxis[face]] += kSign[face];
          if (!grid.at(neighbour[0], neighbour[1], neighbour[2])) visit(x, y, z, face);
        }
      }
}

// The 4 lattice corners of a face, counter-clockwise seen from outside.
std::array<std::array<int, 3>, 4> face_corners(int x, int y, int z, int face) {
  const int axis = kAxis[face], u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::array<int, 3> base = {x, y, z};
  if (kSign[face] > 0) base[axis] += 1;
  std::array<std::array<int, 3>, 4> corners;
  for (int c = 0; c < 4; ++c) {
    corners[c] = base;
    const int du = (c == 1 || c == 2), dv = (c >= 2);
    corners[c][u] += du;
    corners[c][v] += dv;
  }
  // (u, v, axis) is right-handed, so 0-1-2-3 winds counter-clockwise about +axis.
  if (kSign[face] < 0) std::swap(corners[1], corners[3]);
  return corners;
}

}  // namespace

TriangleMesh exposed_faces(const VoxelGrid& grid) {
  std::unordered_map<std::uint64_t, int> vertex_of;
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
  const auto vertex = [&](const std::array<int, 3>& c) {
    const std::uint64_t key = (std::uint64_t(c[0]) << 42) | (std::uint64_t(c[1]) << 21) | std::uint64_t(c[2]);
    const auto [it, added] = vertex_of.try_emplace(key, static_cast<int>(positions.size()));
    if (added) positions.push_back(grid.origin + grid.voxel_size * Vec3(c[0], c[1], c[2]));
    return it->second;
  };
  for_each_exposed_face(grid, [&](int x, int y, int z, int face) {
    const auto corners = face_corners(x, y, z, face);
    const int a = vertex(corners[0]), b = vertex(corners[1]), c = vertex(corners[2]), d = vertex(corners[3]);
    triangles.push_back({a, b, c});
    triangles.push_back({a, c, d});
  });
  return TriangleMesh(std::move(positions), std::move(triangles), "voxel exposed faces");
}

SampleSet exposed_face_samples(const VoxelGrid& grid) {
  SampleSet samples;
  samples.kind = "voxel faces";
  const double area = grid.voxel_size * grid.voxel_size;
  for_each_exposed_face(grid, [&](int x, int y, int z, int face) {
    Vec3 centre = grid.origin + grid.voxel_size * Vec3(x + 0.5, y + 0.5, z + 0.5);
    Vec3 normal = Vec3::Zero();
    normal[kAxis[face]] = kSign[face];
    samples.positions.push_back(centre + 0.5 * grid.voxel_size * normal);
    samples.normals.push_back(normal);
    samples.weights.push_back(area);
    samples.elements.push_back(static_cast<std::uint32_t>(samples.elements.size()));  // exposed face k
  });
  return samples;
}

}  // namespace roving
