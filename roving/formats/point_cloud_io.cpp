// Point-cloud files: PLY through the strict PLY reader, XYZ by hand.
#include "roving/formats/point_cloud_io.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "ply_reader.h"
#include "roving/core/error.h"
#include "roving/formats/file_bytes.h"
#include "roving/formats/atomic_file.h"

namespace roving {
namespace {

void validate(PointCloud& cloud, const std::string& path) {
  if (cloud.positions.empty()) throw Error(fmt::format("{}: no points; expected a point cloud", path));
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    if (!cloud.positions[i].allFinite())
      throw Error(fmt::format("{}: point {} has a non-finite coordinate", path, i));
  }
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    const double length = cloud.normals[i].norm();
    if (!std::isfinite(length) || length < 1e-12) {
      throw Error(
          fmt::format("{}: point {} has a normal of length {}; expected a direction", path, i, length));
    }
    cloud.normals[i] /= length;
  }
}

PointCloud read_xyz(const std::string& path) {
  require_regular_file(path, "a .xyz point cloud");
  std::ifstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open for reading", path));
  PointCloud cloud;
  std::string line;
  int columns = 0;
  for (std::size_t line_number = 1; std::getline(file, line); ++line_number) {
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
    if (columns == 0) columns = static_cast<int>(values.size());
    if ((values.size() != 3 && values.size() != 6) || static_cast<int>(values.size()) != columns) {
      throw Error(fmt::format("{}:{}: expected {} numbers (x y z [nx ny nz]) like the first point, found {}",
                              path, line_number, columns == 0 ? 3 : columns, values.size()));
    }
    cloud.positions.emplace_back(values[0], values[1], values[2]);
    if (columns == 6) cloud.normals.emplace_back(values[3], values[4], values[5]);
  }
  return cloud;
}

PointCloud read_ply_points(const std::string& path) {
  PlyContents ply = read_ply(path);
  if (ply.declares_faces) {
    throw Error(fmt::format("{}: declares faces; expected a point cloud (read it as a mesh)", path));
  }
  return PointCloud{ply.mesh.mesh.positions(), std::move(ply.normals)};
}

}  // namespace

bool is_ply_point_cloud(const std::string& path) {
  return ply_declares_no_faces(path);
}

PointCloud read_point_cloud(const std::string& path) {
  const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  PointCloud cloud = ext == ".ply" || ext == ".PLY" ? read_ply_points(path) : read_xyz(path);
  validate(cloud, path);
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
