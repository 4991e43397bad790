// Point-cloud files: PLY through the strict PLY reader, XYZ by hand.
#include "roving/formats/points_voxels_patches/point_cloud_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "roving/formats/meshes/ply_reader.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {
namespace {

void validate(PointCloud& cloud, const std::string& path, bool unit_normals) {
  if (cloud.positions.empty()) throw Error(fmt::format("{}: no points; expected a point cloud", path));
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (!cloud.positions[i].allFinite())
      throw Error(fmt::format("{}: point {} has a non-finite coordinate", path, i));
  }
  if (!unit_normals) return;
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    const double length = cloud.normals[i].norm();
    if (!std::isfinite(length) || length < 1e-12) {
      throw Error(
          fmt::format("{}: point {} has a normal of length {}; expected a direction", path, i, length));
    }
    cloud.normals[i] /= length;
  }
}

// XYZ columns by role; the header line names them, else 3 or 6 numbers are x y z [nx ny nz].
enum Column { X, Y, Z, NX, NY, NZ, R, G, B, kColumns };

// The columns a first comment line names ("# x y z r g b", "//X,Y,Z,R,G,B,Nx,Ny,Nz"), or an empty
// list when it is not such a line. Throws when it names x, y and z but something else is off.
std::vector<Column> header_columns(std::string line, const std::string& path) {
  const std::size_t start = line.rfind("//", 0) == 0 ? 2 : line.rfind('#', 0) == 0 ? 1 : std::string::npos;
  if (start == std::string::npos) return {};
  for (char& c : line) c = c == ',' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::pair<const char*, Column> kNames[] = {{"x", X},   {"y", Y},   {"z", Z},     {"nx", NX},
                                                          {"ny", NY}, {"nz", NZ}, {"r", R},     {"g", G},
                                                          {"b", B},   {"red", R}, {"green", G}, {"blue", B}};
  std::vector<Column> columns;
  std::istringstream words(line.substr(start));
  for (std::string word; words >> word;) {
    const auto named =
        std::find_if(std::begin(kNames), std::end(kNames), [&](const auto& n) { return word == n.first; });
    if (named == std::end(kNames)) return {};  // a plain comment
    if (std::find(columns.begin(), columns.end(), named->second) != columns.end()) {
      throw Error(fmt::format("{}:1: the header names column '{}' twice", path, word));
    }
    columns.push_back(named->second);
  }
  const auto has = [&](std::initializer_list<Column> set) {
    return std::count_if(set.begin(), set.end(),
                         [&](Column c) { return std::count(columns.begin(), columns.end(), c); });
  };
  if (has({X, Y, Z}) != 3) return {};
  if (has({NX, NY, NZ}) % 3 != 0 || has({R, G, B}) % 3 != 0) {
    throw Error(
        fmt::format("{}:1: the header names some of nx ny nz or r g b; expected all three or none", path));
  }
  return columns;
}

PointCloud read_xyz(const std::string& path) {
  require_regular_file(path, "a .xyz point cloud");
  std::ifstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  PointCloud cloud;
  std::string line;
  std::vector<Column> columns;
  bool normals = false, colours = false;
  for (std::size_t line_number = 1; std::getline(file, line); ++line_number) {
    if (line_number == 1 && !(columns = header_columns(line, path)).empty()) {
      normals = std::count(columns.begin(), columns.end(), NX);
      colours = std::count(columns.begin(), columns.end(), R);
      continue;
    }
    std::istringstream words(line);
    std::vector<double> values;
    for (std::string token; words >> token;) {
      if (token[0] == '#') break;
      double value = 0;
      const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (error != std::errc() || end != token.data() + token.size()) {
        throw Error(fmt::format("{}:{}: expected numbers, found '{}'", path, line_number, token));
      }
      values.push_back(value);
    }
    if (values.empty()) continue;
    if (columns.empty()) {
      if (values.size() != 3 && values.size() != 6) {
        throw Error(
            fmt::format("{}:{}: expected 3 or 6 numbers (x y z [nx ny nz]), found {}; for other columns "
                        "name them on the first line ('# x y z r g b')",
                        path, line_number, values.size()));
      }
      columns = {X, Y, Z};
      if (values.size() == 6) columns.insert(columns.end(), {NX, NY, NZ}), normals = true;
    }
    if (values.size() != columns.size()) {
      throw Error(fmt::format("{}:{}: expected {} numbers like the first point, found {}", path, line_number,
                              columns.size(), values.size()));
    }
    double v[kColumns];
    for (std::size_t k = 0; k < columns.size(); ++k) v[columns[k]] = values[k];
    cloud.positions.emplace_back(v[X], v[Y], v[Z]);
    if (normals) cloud.normals.emplace_back(v[NX], v[NY], v[NZ]);
    if (colours) {
      if (!(v[R] >= 0 && v[R] <= 255 && v[G] >= 0 && v[G] <= 255 && v[B] >= 0 && v[B] <= 255)) {
        throw Error(fmt::format("{}:{}: colour ({}, {}, {}); expected code values within [0, 255]", path,
                                line_number, v[R], v[G], v[B]));
      }
      cloud.colours.emplace_back(float(v[R]), float(v[G]), float(v[B]));
    }
  }
  return cloud;
}

PointCloud read_ply_points(const std::string& path, std::size_t* non_finite_dropped = nullptr) {
  PlyContents ply = read_ply(path, non_finite_dropped != nullptr);
  if (non_finite_dropped) *non_finite_dropped = ply.non_finite_dropped;
  if (ply.declares_faces) {
    throw Error(fmt::format("{}: declares faces; expected a point cloud (read it as a mesh)", path));
  }
  PointCloud cloud;
  cloud.colours = ply.mesh.mesh.release_vertex_colours();  // moved, as the positions
  cloud.positions = ply.mesh.mesh.release_geometry();  // moved, not copied
  cloud.normals = std::move(ply.normals);
  return cloud;
}

}  // namespace

bool is_ply_point_cloud(const std::string& path) {
  return ply_declares_no_faces(path);
}

bool read_as_ply(const std::string& path) {
  const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  return ext == ".ply" || ext == ".PLY";
}

PointCloud read_point_cloud(const std::string& path, bool unit_normals) {
  PointCloud cloud = read_as_ply(path) ? read_ply_points(path) : read_xyz(path);
  validate(cloud, path, unit_normals);
  return cloud;
}

PointCloud read_point_cloud_finite(const std::string& path, std::size_t& dropped) {
  std::size_t dropped_as_read = 0;
  PointCloud cloud = read_as_ply(path) ? read_ply_points(path, &dropped_as_read) : read_xyz(path);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (!cloud.positions[i].allFinite()) continue;
    cloud.positions[kept] = cloud.positions[i];
    if (!cloud.normals.empty()) cloud.normals[kept] = cloud.normals[i];
    if (!cloud.colours.empty()) cloud.colours[kept] = cloud.colours[i];
    ++kept;
  }
  dropped = dropped_as_read + cloud.positions.size() - kept;
  cloud.positions.resize(kept);
  if (!cloud.normals.empty()) cloud.normals.resize(kept);
  if (!cloud.colours.empty()) cloud.colours.resize(kept);
  if (kept == 0 && dropped > 0) {
    throw Error(fmt::format("{}: none of its {} points has finite coordinates; expected a point cloud", path, dropped));
  }
  validate(cloud, path, false);
  return cloud;
}

void write_point_cloud_ply(const PointCloud& cloud, const std::string& path) {
  std::ostringstream file;
  const bool normals = cloud.normals.size() == cloud.positions.size();
  file << "ply\nformat ascii 1.0\nelement vertex " << cloud.positions.size()
       << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) file << "property float nx\nproperty float ny\nproperty float nz\n";
  file << "end_header\n";
  file.precision(9);
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    const Vec3& p = cloud.positions[i];
    file << p.x() << ' ' << p.y() << ' ' << p.z();
    if (normals)
      file << ' ' << cloud.normals[i].x() << ' ' << cloud.normals[i].y() << ' ' << cloud.normals[i].z();
    file << '\n';
  }
  AtomicFile out(path);
  const std::string text = file.str();
  std::fwrite(text.data(), 1, text.size(), out.stream());
  out.commit();
}

}  // namespace roving
