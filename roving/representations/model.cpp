// Loading models of every representation and taking samples from them.
#include "roving/representations/model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <numeric>

#include "roving/core/error.h"
#include "roving/formats/points_voxels_patches/binvox.h"
#include "roving/formats/points_voxels_patches/bpt.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"
#include "roving/representations/bezier_surface.h"
#include "roving/representations/point_normals.h"
#include "roving/representations/voxel_surface.h"

namespace roving {
namespace {

std::string lower_extension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

ModelType type_by_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "binvox") return ModelType::Voxels;
  if (ext == "xyz") return ModelType::Points;
  if (ext == "bpt") return ModelType::Bezier;
  if (ext == "ply" && is_ply_point_cloud(path)) return ModelType::Points;
  return ModelType::Mesh;  // load_mesh names the file if the extension is unknown
}

void require_extent(const Model& model, const std::string& path) {
  const double extent = model.bounding_box().diagonal();
  if (!(extent > 0) || !std::isfinite(extent)) {
    throw Error(fmt::format("{}: the model has no extent (bounding-box diagonal {}); expected a shape", path,
                            extent));
  }
}

SampleSet samples_of(const Model& reference, const SampleSpec& spec);

}  // namespace

const char* to_string(ModelType type) {
  switch (type) {
    case ModelType::Mesh: return "mesh";
    case ModelType::Points: return "points";
    case ModelType::Voxels: return "voxels";
    case ModelType::Bezier: return "bezier";
  }
  return "?";
}

ModelType parse_model_type(const std::string& text, const std::string& option) {
  for (ModelType t : {ModelType::Mesh, ModelType::Points, ModelType::Voxels, ModelType::Bezier}) {
    if (text == to_string(t)) return t;
  }
  throw Error(fmt::format("{}: expected mesh, points, voxels or bezier, found '{}'", option, text));
}

BoundingBox Model::bounding_box() const {
  if (type != ModelType::Points) return mesh.mesh.bounding_box();
  BoundingBox box;
  for (const Vec3& p : points.positions) box.extend(p);
  return box;
}

Model load_model(const std::string& path, std::optional<ModelType> type) {
  Model model;
  model.type = type ? *type : type_by_extension(path);
  switch (model.type) {
    case ModelType::Mesh: model.mesh = load_mesh(path); break;
    case ModelType::Voxels:
      model.voxels = read_binvox(path);
      model.mesh.path = path;
      model.mesh.mesh = exposed_faces(*model.voxels);
      break;
    case ModelType::Bezier: {
      model.bezier = read_bpt(path);
      model.patches_flipped = orient_consistently(*model.bezier);
      BoundingBox net;
      for (const BezierPatch& p : model.bezier->patches) {
        for (const Vec3& c : p.control) net.extend(c);
      }
      Tessellation t;
      try {
        t = tessellate(*model.bezier, 1e-4 * net.diagonal());
      } catch (const Error& e) {
        throw Error(fmt::format("{}: {}", path, e.what()));
      }
      if (t.mesh.triangle_count() == t.mesh.degenerate_triangle_count()) {
        throw Error(fmt::format("{}: the {} Bezier patches have no area; expected a surface", path,
                                model.bezier->patches.size()));
      }
      model.mesh.path = path;
      model.mesh.mesh = std::move(t.mesh);
      model.bezier_cells = t.cells_per_side;
      model.chordal_error_bound = t.chordal_error_bound;
      break;
    }
    case ModelType::Points: return model_from_points(read_point_cloud(path), path);
  }
  require_extent(model, path);
  return model;
}

ModelType model_type_of(const std::string& path) { return type_by_extension(path); }

PointCloud load_point_cloud(const std::string& path, std::optional<ModelType> type) {
  const ModelType found = type ? *type : type_by_extension(path);
  if (found != ModelType::Points) {
    throw Error(fmt::format("{}: expected a point cloud (.xyz, or .ply without faces), found a {} model", path,
                            to_string(found)));
  }
  return read_point_cloud(path, false);
}

Model model_from_mesh(TriangleMesh mesh, const std::string& name) {
  Model model;
  model.mesh.path = name;
  model.mesh.mesh = std::move(mesh);
  require_extent(model, name);
  return model;
}

Model model_from_points(PointCloud points, const std::string& name, bool unit_normals) {
  Model model;
  model.type = ModelType::Points;
  model.mesh.path = name;
  if (points.positions.empty()) throw Error(fmt::format("{}: no points; expected a point cloud", name));
  const auto check = [&](const std::vector<Vec3>& rows, const char* what) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (!rows[i].allFinite()) {
        throw Error(fmt::format("{}: {} {} is not finite ({}, {}, {})", name, what, i, rows[i].x(),
                                rows[i].y(), rows[i].z()));
      }
    }
  };
  check(points.positions, "point");
  check(points.normals, "normal");
  if (!points.normals.empty() && points.normals.size() != points.positions.size()) {
    throw Error(fmt::format("{}: {} normals for {} points; expected one per point or none", name,
                            points.normals.size(), points.positions.size()));
  }
  if (!points.colours.empty() && points.colours.size() != points.positions.size()) {
    throw Error(fmt::format("{}: {} colours for {} points; expected one per point or none", name,
                            points.colours.size(), points.positions.size()));
  }
  for (Vec3& n : points.normals) {
    if (!unit_normals) break;
    if (!(n.norm() > 0)) throw Error(fmt::format("{}: a normal is zero; expected non-zero normals", name));
    n.normalize();
  }
  model.points = std::move(points);
  require_extent(model, name);
  if (model.points.normals.empty()) {
    try {
      model.points.normals = estimate_normals(model.points.positions);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", name, e.what()));
    }
    model.normals_estimated = true;
  }
  return model;
}

namespace {

// make(), with the file named in its errors: the sampling code knows only the surface.
template <class Make>
SampleSet naming_the_file(const Model& reference, const Make& make) {
  try {
    return make();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind(reference.path(), 0) == 0 || message.rfind("--samples", 0) == 0) throw;
    throw Error(fmt::format("{}: {}", reference.path(), message));
  }
}

}  // namespace

SampleSet reference_samples(const Model& reference, const SampleSpec& spec) {
  return naming_the_file(reference, [&] { return samples_of(reference, spec); });
}

SampleSet reference_samples_releasing(Model& reference, const SampleSpec& spec) {
  if (reference.type != ModelType::Mesh) return reference_samples(reference, spec);
  return naming_the_file(reference, [&] { return make_samples_releasing(reference.mesh.mesh, spec); });
}

namespace {

SampleSet samples_of(const Model& reference, const SampleSpec& spec) {
  switch (reference.type) {
    case ModelType::Mesh: return make_samples(reference.mesh.mesh, spec);
    case ModelType::Voxels:
      if (spec.kind == SampleSpec::Kind::Faces) return exposed_face_samples(*reference.voxels);
      if (spec.kind == SampleSpec::Kind::Area) return make_samples(reference.mesh.mesh, spec);
      throw Error(
          "--samples: a voxel reference is sampled on its exposed faces: expected faces or area:N, found "
          "vertices");
    case ModelType::Bezier: return bezier_samples(*reference.bezier, spec, reference.bezier_cells);
    case ModelType::Points: {
      if (spec.kind == SampleSpec::Kind::Area) {
        throw Error(
            fmt::format("--samples: a point-cloud reference is sampled at its points: expected faces or "
                        "vertices, found '{}'",
                        spec.to_string()));
      }
      SampleSet samples;
      samples.kind = "points";
      samples.positions = reference.points.positions;
      samples.normals = reference.points.normals;
      samples.weights.assign(samples.positions.size(), 1.0);  // no area: plain means
      samples.elements.resize(samples.positions.size());
      std::iota(samples.elements.begin(), samples.elements.end(), 0u);
      return samples;
    }
  }
  throw Error("unknown model type");
}

}  // namespace

const TriangleMesh& test_surface(const Model& test) {
  if (test.type != ModelType::Points) return test.mesh.mesh;
  if (!test.surfels) test.surfels = make_surfels(test.points, test.path());
  return test.surfels->mesh;
}

}  // namespace roving
