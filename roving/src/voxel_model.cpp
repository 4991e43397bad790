// binvox I/O, exposed faces and face samples of voxel models.
#include "roving/voxel_model.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "roving/error.h"

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

std::size_t VoxelGrid::occupied_count() const {
  return static_cast<std::size_t>(std::count(occupied.begin(), occupied.end(), std::uint8_t{1}));
}

VoxelGrid read_binvox(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  const auto fail = [&](const std::string& what) { return Error(fmt::format("{}: {}", path, what)); };
  std::string line;
  std::getline(file, line);
  if (line.rfind("#binvox", 0) != 0) throw fail(fmt::format("expected '#binvox 1' first, found '{}'", line.substr(0, 40)));
  VoxelGrid grid;
  bool have_dim = false, have_data = false;
  double scale = 1;
  while (std::getline(file, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "dim") {
      long d[3] = {0, 0, 0};
      if (!(words >> d[0] >> d[1] >> d[2])) throw fail(fmt::format("expected 'dim D D D', found '{}'", line));
      if (d[0] != d[1] || d[1] != d[2] || d[0] < 1 || d[0] > 2048) {
        throw fail(fmt::format("expected a cubic grid 'dim D D D' with D in 1..2048, found '{}'", line));
      }
      grid.dimension = static_cast<int>(d[0]);
      have_dim = true;
    } else if (keyword == "translate") {
      if (!(words >> grid.origin.x() >> grid.origin.y() >> grid.origin.z()) || !grid.origin.allFinite()) {
        throw fail(fmt::format("expected 'translate X Y Z' with finite numbers, found '{}'", line));
      }
    } else if (keyword == "scale") {
      if (!(words >> scale) || !(scale > 0) || !std::isfinite(scale)) {
        throw fail(fmt::format("expected 'scale S' with S > 0, found '{}'", line));
      }
    } else if (keyword == "data") {
      have_data = true;
      break;
    } else {
      throw fail(fmt::format("expected a binvox header line (dim, translate, scale, data), found '{}'", line.substr(0, 40)));
    }
  }
  if (!have_dim || !have_data) throw fail("header ends without 'dim' and 'data'");
  grid.voxel_size = scale / grid.dimension;
  const std::size_t total = static_cast<std::size_t>(grid.dimension) * grid.dimension * grid.dimension;
  grid.occupied.assign(total, 0);
  std::size_t filled = 0;
  unsigned char pair[2];
  while (filled < total && file.read(reinterpret_cast<char*>(pair), 2)) {
    if (pair[1] == 0 || pair[0] > 1) {
      throw fail(fmt::format("run {} at voxel {}: expected (value 0 or 1, count 1..255), found ({}, {})",
                             filled, filled, int(pair[0]), int(pair[1])));
    }
    if (filled + pair[1] > total) throw fail(fmt::format("runs overflow the {}^3 grid", grid.dimension));
    std::fill_n(grid.occupied.begin() + filled, pair[1], pair[0]);
    filled += pair[1];
  }
  if (filled < total) {
    throw fail(fmt::format("truncated: runs cover {} of the {} voxels of a {}^3 grid", filled, total, grid.dimension));
  }
  if (grid.occupied_count() == 0) throw fail("no occupied voxel; expected a shape");
  return grid;
}

void write_binvox(const VoxelGrid& grid, const std::string& path) {
  std::ofstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("{}: cannot open for writing", path));
  file << "#binvox 1\ndim " << grid.dimension << ' ' << grid.dimension << ' ' << grid.dimension << "\n";
  file.precision(17);
  file << "translate " << grid.origin.x() << ' ' << grid.origin.y() << ' ' << grid.origin.z() << "\n";
  file << "scale " << grid.voxel_size * grid.dimension << "\ndata\n";
  for (std::size_t i = 0; i < grid.occupied.size();) {
    const std::uint8_t value = grid.occupied[i];
    std::size_t run = 1;
    while (run < 255 && i + run < grid.occupied.size() && grid.occupied[i + run] == value) ++run;
    file.put(static_cast<char>(value));
    file.put(static_cast<char>(run));
    i += run;
  }
  if (!file) throw Error(fmt::format("{}: write failed", path));
}

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
  });
  return samples;
}

}  // namespace roving
