// OBJ + MTL and glTF writers for coloured and textured meshes.
#include "roving/formats/outputs/coloured_mesh_writer.h"

#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "roving/core/colour_science.h"
#include "roving/core/error.h"
#include "roving/formats/files/atomic_file.h"

namespace roving {
namespace {

namespace fs = std::filesystem;

// The materials as written: the mesh's, or one white material where it has none.
std::vector<Material> materials_of(const TriangleMesh& mesh) {
  if (const TextureMapping* mapping = mesh.texture_mapping()) return mapping->materials;
  return std::vector<Material>(1);
}

int material_of(const TriangleMesh& mesh, std::size_t face) {
  const TextureMapping* mapping = mesh.texture_mapping();
  return mapping ? mapping->face_material[face] : 0;
}

void require_texture_files(const TriangleMesh& mesh, const std::string& path,
                           const std::vector<std::string>& texture_files) {
  const std::vector<Material> materials = materials_of(mesh);
  if (texture_files.size() != materials.size()) {
    throw Error(fmt::format("{}: {} texture file names for {} materials", path, texture_files.size(),
                            materials.size()));
  }
  for (std::size_t m = 0; m < materials.size(); ++m) {
    if (bool(materials[m].texture) != !texture_files[m].empty()) {
      throw Error(fmt::format("{}: material {} {} a texture but its file name is {}", path, m,
                              materials[m].texture ? "has" : "has no",
                              texture_files[m].empty() ? "empty" : "given"));
    }
  }
}

}  // namespace

void write_coloured_obj(const TriangleMesh& mesh, const std::string& path, const std::string& mtl_path,
                        const std::vector<std::string>& texture_files) {
  require_texture_files(mesh, path, texture_files);
  const std::vector<Material> materials = materials_of(mesh);
  AtomicFile mtl(mtl_path);
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const Material& material = materials[m];
    fmt::print(mtl.stream(), "newmtl m{}\nKd {} {} {}\n", m, material.factor.x() / 255,
               material.factor.y() / 255, material.factor.z() / 255);
    if (!material.texture) continue;
    const Sampler& s = material.sampler;
    if (s.wrap_s != s.wrap_t || s.wrap_s == Wrap::MirroredRepeat || s.filter != Filter::Linear) {
      throw Error(
          fmt::format("{}: material {}'s sampler (mirrored repeat, nearest filtering or a wrap mode per "
                      "axis) has no MTL equivalent; write glTF",
                      path, m));
    }
    fmt::print(mtl.stream(), "map_Kd {}{}\n", s.wrap_s == Wrap::ClampToEdge ? "-clamp on " : "",
               texture_files[m]);
  }
  mtl.close_stream();

  AtomicFile obj(path);
  std::FILE* out = obj.stream();
  fmt::print(out, "# written by roving\nmtllib {}\n", fs::path(mtl_path).filename().string());
  const std::vector<Colour>& colours = mesh.vertex_colours();
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions()[v];
    if (colours.empty()) {
      fmt::print(out, "v {} {} {}\n", p.x(), p.y(), p.z());
    } else {
      fmt::print(out, "v {} {} {} {} {} {}\n", p.x(), p.y(), p.z(), colours[v].x() / 255,
                 colours[v].y() / 255, colours[v].z() / 255);
    }
  }
  const TextureMapping* mapping = mesh.texture_mapping();
  if (mapping) {
    for (const TexCoord& uv : mapping->corner_uv) fmt::print(out, "vt {} {}\n", uv.x(), 1 - uv.y());
  }
  int current = -1;
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    if (material_of(mesh, f) != current) fmt::print(out, "usemtl m{}\n", current = material_of(mesh, f));
    const Triangle& t = mesh.triangles()[f];
    if (mapping) {
      fmt::print(out, "f {}/{} {}/{} {}/{}\n", t[0] + 1, 3 * f + 1, t[1] + 1, 3 * f + 2, t[2] + 1, 3 * f + 3);
    } else {
      fmt::print(out, "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
  }
  obj.close_stream();
  mtl.commit();
  obj.commit();
}

void write_coloured_gltf(const TriangleMesh& mesh, const std::string& path,
                         const std::vector<std::string>& texture_files) {
  require_texture_files(mesh, path, texture_files);
  const std::vector<Material> materials = materials_of(mesh);
  const TextureMapping* mapping = mesh.texture_mapping();
  const std::vector<Colour>& colours = mesh.vertex_colours();
  // Per material, its vertices (a mesh vertex once per distinct texture coordinate) and triangles.
  struct Part {
    std::vector<float> positions, uv, colour;
    std::vector<std::uint32_t> indices;
    std::map<std::tuple<int, double, double>, std::uint32_t> index_of;
  };
  std::vector<Part> parts(materials.size());
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    Part& part = parts[material_of(mesh, f)];
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.triangles()[f][c];
      const TexCoord uv = mapping ? mapping->corner_uv[3 * f + c] : TexCoord::Zero();
      const auto [it, added] = part.index_of.try_emplace(
          {v, uv.x(), uv.y()}, static_cast<std::uint32_t>(part.positions.size() / 3));
      if (added) {
        const Vec3& p = mesh.positions()[v];
        part.positions.insert(part.positions.end(), {float(p.x()), float(p.y()), float(p.z())});
        part.uv.insert(part.uv.end(), {float(uv.x()), float(uv.y())});
        if (!colours.empty()) {
          for (int k = 0; k < 3; ++k) part.colour.push_back(float(srgb_linear(colours[v][k])));
        }
      }
      part.indices.push_back(it->second);
    }
  }
  const std::string bin_path = fs::path(path).replace_extension(".bin").string();
  std::string bin;
  nlohmann::json accessors = nlohmann::json::array(), views = nlohmann::json::array();
  // Appends `data` as a buffer view and an accessor of `type`; returns the accessor's index.
  const auto add = [&](const auto& data, const char* type, int component_type, std::size_t count,
                       bool bounds) {
    while (bin.size() % 4) bin.push_back('\0');
    const std::size_t bytes = data.size() * sizeof data[0];
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    bin.append(reinterpret_cast<const char*>(data.data()), bytes);
    nlohmann::json accessor = {{"bufferView", views.size() - 1},
                               {"componentType", component_type},
                               {"count", count},
                               {"type", type}};
    if (bounds) {  // POSITION needs its min and max
      std::array<float, 3> low{}, high{};
      for (std::size_t k = 0; k < 3; ++k) {
        low[k] = high[k] = count ? float(data[k]) : 0.0f;
        for (std::size_t i = 0; i < count; ++i) {
          low[k] = std::min(low[k], float(data[3 * i + k]));
          high[k] = std::max(high[k], float(data[3 * i + k]));
        }
      }
      accessor["min"] = low;
      accessor["max"] = high;
    }
    accessors.push_back(accessor);
    return accessors.size() - 1;
  };
  nlohmann::json primitives = nlohmann::json::array(), gltf_materials = nlohmann::json::array();
  nlohmann::json images = nlohmann::json::array(), textures = nlohmann::json::array();
  nlohmann::json samplers = nlohmann::json::array();
  for (std::size_t m = 0; m < materials.size(); ++m) {
    const Material& material = materials[m];
    nlohmann::json pbr = {{"baseColorFactor",
                           {srgb_linear(material.factor.x()), srgb_linear(material.factor.y()),
                            srgb_linear(material.factor.z()), 1.0}}};
    if (material.texture) {
      const auto wrap = [](Wrap w) {
        return w == Wrap::Repeat ? 10497 : w == Wrap::ClampToEdge ? 33071 : 33648;
      };
      const Sampler& s = material.sampler;
      const int filter = s.filter == Filter::Linear ? 9729 : 9728;
      samplers.push_back({{"wrapS", wrap(s.wrap_s)},
                          {"wrapT", wrap(s.wrap_t)},
                          {"magFilter", filter},
                          {"minFilter", filter}});
      images.push_back({{"uri", texture_files[m]}});
      textures.push_back({{"source", images.size() - 1}, {"sampler", samplers.size() - 1}});
      pbr["baseColorTexture"] = {{"index", textures.size() - 1}};
    }
    gltf_materials.push_back({{"name", material.name.empty() ? fmt::format("m{}", m) : material.name},
                              {"pbrMetallicRoughness", pbr}});
    const Part& part = parts[m];
    if (part.indices.empty()) continue;
    const std::size_t vertices = part.positions.size() / 3;
    nlohmann::json attributes = {{"POSITION", add(part.positions, "VEC3", 5126, vertices, true)}};
    if (material.texture) attributes["TEXCOORD_0"] = add(part.uv, "VEC2", 5126, vertices, false);
    if (!part.colour.empty()) attributes["COLOR_0"] = add(part.colour, "VEC3", 5126, vertices, false);
    const std::size_t indices = add(part.indices, "SCALAR", 5125, part.indices.size(), false);
    primitives.push_back({{"attributes", attributes}, {"indices", indices}, {"material", m}, {"mode", 4}});
  }
  nlohmann::json document = {
      {"asset", {{"version", "2.0"}, {"generator", "roving"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", primitives}}}},
      {"materials", gltf_materials},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", fs::path(bin_path).filename().string()}, {"byteLength", bin.size()}}}}};
  if (!images.empty())
    document["images"] = images, document["textures"] = textures, document["samplers"] = samplers;
  AtomicFile buffer(bin_path), gltf(path);
  if (std::fwrite(bin.data(), 1, bin.size(), buffer.stream()) != bin.size()) {
    throw Error(fmt::format("{}: cannot write the buffer", bin_path));
  }
  buffer.close_stream();
  const std::string text = document.dump(1) + "\n";
  std::fputs(text.c_str(), gltf.stream());
  gltf.close_stream();
  buffer.commit();
  gltf.commit();
}

}  // namespace roving
