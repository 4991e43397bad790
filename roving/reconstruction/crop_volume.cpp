#include "roving/reconstruction/crop_volume.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "roving/core/error.h"

namespace roving {

CropVolume::CropVolume(int axis, double axis_min, double axis_max, std::vector<Vec3> polygon,
                       const std::string& source)
    : w_(axis), axis_min_(axis_min), axis_max_(axis_max), polygon_(std::move(polygon)) {
  if (axis < 0 || axis > 2) throw Error(fmt::format("{}: orthogonal axis {}; expected 0, 1 or 2", source, axis));
  // Open3D's pairs: x -> (y, z), y -> (x, z), z -> (x, y).
  u_ = axis == 0 ? 1 : 0;
  v_ = axis == 2 ? 1 : 2;
  if (!std::isfinite(axis_min) || !std::isfinite(axis_max) || axis_min > axis_max) {
    throw Error(fmt::format("{}: axis_min {} and axis_max {}; expected finite numbers, axis_min <= axis_max", source,
                            axis_min, axis_max));
  }
  if (polygon_.size() < 3) {
    throw Error(fmt::format("{}: bounding_polygon has {} vertices; expected a closed polygon of 3 or more", source,
                            polygon_.size()));
  }
  for (const Vec3& p : polygon_) {
    if (!p.allFinite()) {
      throw Error(fmt::format("{}: bounding_polygon holds ({}, {}, {}); expected finite numbers", source, p.x(), p.y(),
                              p.z()));
    }
  }
}

bool CropVolume::contains(const Vec3& p) const {
  if (p[w_] < axis_min_ || p[w_] > axis_max_) return false;
  // Where the edges cross the point's line along u, counted below its u as Open3D counts them:
  // the crossings sorted, the point's place among them by lower_bound. Every crossing's value is
  // computed by Open3D's expression in its order, so that ties fall the same way.
  const double pu = p[u_], pv = p[v_];
  std::size_t below = 0;
  const std::size_t n = polygon_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 &a = polygon_[i], &b = polygon_[(i + 1) % n];
    if ((a[v_] < pv && b[v_] >= pv) || (b[v_] < pv && a[v_] >= pv)) {
      const double node = a[u_] + (pv - a[v_]) / (b[v_] - a[v_]) * (b[u_] - a[u_]);
      if (node < pu) ++below;  // lower_bound's place: the crossings strictly below
    }
  }
  return below % 2 == 1;
}

namespace {

double number(const nlohmann::json& json, const char* key, const std::string& path) {
  const auto it = json.find(key);
  if (it == json.end() || !it->is_number()) {
    throw Error(fmt::format("{}: '{}' is {}; expected a number", path, key,
                            it == json.end() ? std::string("missing") : std::string(it->type_name())));
  }
  return it->get<double>();
}

}  // namespace

CropVolume read_crop_volume(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot read the crop volume", path));
  std::ostringstream text;
  text << in.rdbuf();
  const nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, false);
  if (json.is_discarded() || !json.is_object()) {
    throw Error(fmt::format("{}: expected Open3D's SelectionPolygonVolume as a JSON object; found no such JSON", path));
  }
  const auto class_name = json.find("class_name");
  if (class_name == json.end() || *class_name != "SelectionPolygonVolume") {
    throw Error(fmt::format("{}: class_name is {}; expected \"SelectionPolygonVolume\"", path,
                            class_name == json.end() ? std::string("missing") : class_name->dump()));
  }
  const auto version = [&](const char* key, int expected) {
    const auto it = json.find(key);
    if (it != json.end() && !(it->is_number_integer() && it->get<long long>() == expected)) {
      throw Error(fmt::format("{}: {} is {}; expected {}", path, key, it->dump(), expected));
    }
  };
  version("version_major", 1);
  version("version_minor", 0);
  const auto axis_name = json.find("orthogonal_axis");
  const std::string axis = axis_name != json.end() && axis_name->is_string() ? axis_name->get<std::string>() : "";
  if (axis.size() != 1 || std::string("xyzXYZ").find(axis) == std::string::npos) {
    throw Error(fmt::format("{}: orthogonal_axis is {}; expected \"X\", \"Y\" or \"Z\"", path,
                            axis_name == json.end() ? std::string("missing") : axis_name->dump()));
  }
  const auto polygon_json = json.find("bounding_polygon");
  if (polygon_json == json.end() || !polygon_json->is_array()) {
    throw Error(fmt::format("{}: bounding_polygon is {}; expected an array of [x, y, z] vertices", path,
                            polygon_json == json.end() ? std::string("missing") : std::string(polygon_json->type_name())));
  }
  std::vector<Vec3> polygon;
  for (const nlohmann::json& vertex : *polygon_json) {
    if (!vertex.is_array() || vertex.size() != 3 ||
        !std::all_of(vertex.begin(), vertex.end(), [](const nlohmann::json& c) { return c.is_number(); })) {
      throw Error(fmt::format("{}: bounding_polygon's vertex {} is {}; expected [x, y, z]", path, polygon.size(),
                              vertex.dump()));
    }
    polygon.emplace_back(vertex[0].get<double>(), vertex[1].get<double>(), vertex[2].get<double>());
  }
  const int w = std::tolower(static_cast<unsigned char>(axis[0])) - 'x';
  return CropVolume(w, number(json, "axis_min", path), number(json, "axis_max", path), std::move(polygon), path);
}

}  // namespace roving
