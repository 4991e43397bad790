// binvox files: the voxel format of Min's binvox (run-length encoded, y fastest, then z, then x).
#include "roving/formats/points_voxels_patches/binvox.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/files/atomic_file.h"

namespace roving {

VoxelGrid read_binvox(const std::string& path) {
  require_regular_file(path, "a .binvox voxel model");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  const auto fail = [&](const std::string& what) { return Error(fmt::format("{}: {}", path, what)); };
  std::string line;
  std::getline(file, line);
  if (line.rfind("#binvox", 0) != 0)
    throw fail(fmt::format("expected '#binvox 1' first, found '{}'", line.substr(0, 40)));
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
      throw fail(fmt::format("expected a binvox header line (dim, translate, scale, data), found '{}'",
                             line.substr(0, 40)));
    }
  }
  if (!have_dim || !have_data) throw fail("header ends without 'dim' and 'data'");
  grid.voxel_size = scale / grid.dimension;
  const std::size_t total = static_cast<std::size_t>(grid.dimension) * grid.dimension * grid.dimension;
  // Each 2-byte run covers at most 255 voxels: check that the data can fill the grid, and that
  // the grid fits in memory, before allocating it.
  const std::streamoff data_start = file.tellg();
  file.seekg(0, std::ios::end);
  const auto data_bytes = static_cast<std::size_t>(file.tellg() - data_start);
  file.seekg(data_start);
  if (data_bytes / 2 * 255 < total) {
    throw fail(fmt::format("truncated: {} bytes of runs cover at most {} voxels; the {}^3 grid has {}",
                           data_bytes, data_bytes / 2 * 255, grid.dimension, total));
  }
  require_memory(fmt::format("{}: reading", path), double(total),
                 fmt::format("a {}^3 voxel grid", grid.dimension));
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
    throw fail(fmt::format("truncated: runs cover {} of the {} voxels of a {}^3 grid", filled, total,
                           grid.dimension));
  }
  if (grid.occupied_count() == 0) throw fail("no occupied voxel; expected a shape");
  return grid;
}

void write_binvox(const VoxelGrid& grid, const std::string& path) {
  std::ostringstream file;
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
  AtomicFile out(path);
  const std::string bytes = file.str();
  std::fwrite(bytes.data(), 1, bytes.size(), out.stream());
  out.commit();
}

}  // namespace roving
