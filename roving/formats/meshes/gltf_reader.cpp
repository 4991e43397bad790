// glTF 2.0 reader: the scene's node graph walked, each mesh's triangles placed by its node's
// transform, colour taken from COLOR_0 and the materials; every byte read through the checked
// document (gltf_document.h).
#include "roving/formats/meshes/gltf_reader.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "roving/core/colour_science.h"
#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/images_and_matlab/texture_io.h"
#include "roving/formats/meshes/gltf_document.h"

namespace roving {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// The triangles of every mesh the scene places, with their colour, from the document.
class GltfReader : private GltfDocument {
 public:
  explicit GltfReader(const std::string& path) : GltfDocument(path) {}

  LoadedMesh read() {
    check_version_and_extensions();
    for (std::size_t node : scene_roots()) place(node, Eigen::Matrix4d::Identity());
    if (!nodes_present_) {  // no node at all: every mesh where it stands
      for (std::size_t m = 0; m < array("meshes").size(); ++m) place_mesh(m, Eigen::Matrix4d::Identity());
    }
    if (triangles_.empty()) {
      throw Error(
          fmt::format("{}: no faces found ({} primitives of points or lines, which are not surfaces); "
                      "expected a triangle mesh",
                      path(), skipped_primitives_));
    }
    LoadedMesh loaded;
    loaded.path = path();
    loaded.dropped_repeated_vertex_faces = dropped_faces_;
    loaded.mesh = TriangleMesh(std::move(positions_), std::move(triangles_), path());  // checks finite values
    if (any_vertex_colour_) loaded.mesh.set_vertex_colours(std::move(vertex_colours_), path());
    if (any_material_colour_) {
      align_material_arrays(loaded.mesh.triangle_count());
      TextureMapping mapping;
      // Only the materials some face uses (glTF's default among them where it is).
      std::vector<int> renumbered(materials_.size(), -1);
      for (int& m : face_material_) {
        if (renumbered[m] < 0) {
          renumbered[m] = static_cast<int>(mapping.materials.size());
          mapping.materials.push_back(materials_[m]);
        }
        m = renumbered[m];
      }
      mapping.face_material = std::move(face_material_);
      mapping.corner_uv = std::move(corner_uv_);
      loaded.mesh.set_texture_mapping(std::move(mapping), path());
    }
    return loaded;
  }

 private:
  // The nodes to start from: the scene's, else every node that is nobody's child.
  std::vector<std::size_t> scene_roots() {
    const json& nodes = array("nodes");
    nodes_present_ = !nodes.empty();
    parent_.assign(nodes.size(), kNone);
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      const std::string where = fmt::format("nodes[{}]", n);
      if (!nodes[n].is_object()) fail(fmt::format("expected {} to be an object", where));
      const json* children = find(nodes[n], "children");
      if (!children) continue;
      if (!children->is_array()) fail(where + ": expected 'children' to be an array");
      for (const json& child : *children) {
        if (!child.is_number_unsigned() || child.get<std::size_t>() >= nodes.size()) {
          fail(fmt::format("{}: child {} is not a node of the {}", where, child.dump(), nodes.size()));
        }
        std::size_t& parent = parent_[child.get<std::size_t>()];
        if (parent != kNone || child.get<std::size_t>() == n) {
          fail(fmt::format("node {} has two parents or is its own; glTF nodes form a tree",
                           child.get<std::size_t>()));
        }
        parent = n;
      }
    }
    std::vector<std::size_t> roots;
    const json& scenes = array("scenes");
    if (!scenes.empty()) {
      const std::size_t s = natural(document(), "scene", "the document", 0);
      const json& scene = element("scenes", s, "scene");
      const json* listed = find(scene, "nodes");
      if (listed && !listed->is_array()) fail(fmt::format("scenes[{}]: expected 'nodes' to be an array", s));
      for (const json& n : listed ? *listed : json::array()) {
        if (!n.is_number_unsigned() || n.get<std::size_t>() >= nodes.size() ||
            parent_[n.get<std::size_t>()] != kNone) {
          fail(fmt::format("scenes[{}] lists {}, which is not a root node", s, n.dump()));
        }
        roots.push_back(n.get<std::size_t>());
      }
    } else {
      for (std::size_t n = 0; n < nodes.size(); ++n) {
        if (parent_[n] == kNone) roots.push_back(n);
      }
    }
    return roots;
  }

  Eigen::Matrix4d local_transform(const json& node, const std::string& where) const {
    const auto numbers = [&](const char* key, std::size_t count) -> std::optional<std::vector<double>> {
      const json* value = find(node, key);
      if (!value) return std::nullopt;
      if (!value->is_array() || value->size() != count)
        fail(fmt::format("{}: expected '{}' of {} numbers", where, key, count));
      std::vector<double> out;
      for (const json& x : *value) {
        if (!x.is_number() || !std::isfinite(x.get<double>()))
          fail(fmt::format("{}: '{}' holds {}", where, key, x.dump()));
        out.push_back(x.get<double>());
      }
      return out;
    };
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (const auto matrix = numbers("matrix", 16)) {
      for (int k = 0; k < 16; ++k) m(k % 4, k / 4) = (*matrix)[k];  // column-major
      return m;
    }
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    if (const auto v = numbers("translation", 3)) t.translate(Vec3((*v)[0], (*v)[1], (*v)[2]));
    if (const auto q = numbers("rotation", 4)) {
      const Eigen::Quaterniond rotation((*q)[3], (*q)[0], (*q)[1], (*q)[2]);  // stored x, y, z, w
      if (!(rotation.norm() > 0)) fail(where + ": a zero rotation quaternion");
      t.rotate(rotation.normalized());
    }
    if (const auto s = numbers("scale", 3)) t.scale(Vec3((*s)[0], (*s)[1], (*s)[2]));
    return t.matrix();
  }

  // Node `root` and its subtree. Every node has at most one parent and none is its own, so the
  // walk visits each node once; a stack of its own, as a chain of nodes may be deep.
  void place(std::size_t root, const Eigen::Matrix4d& parent) {
    std::vector<std::pair<std::size_t, Eigen::Matrix4d>> pending = {{root, parent}};
    while (!pending.empty()) {
      const auto [n, above] = pending.back();
      pending.pop_back();
      if (++placed_nodes_ > array("nodes").size()) fail("the node graph is not a tree");
      const json& node = array("nodes")[n];
      const std::string where = fmt::format("nodes[{}]", n);
      const Eigen::Matrix4d world = above * local_transform(node, where);
      if (find(node, "mesh")) place_mesh(natural(node, "mesh", where), world);
      if (const json* children = find(node, "children")) {
        for (const json& child : *children) pending.emplace_back(child.get<std::size_t>(), world);
      }
    }
  }

  void place_mesh(std::size_t m, const Eigen::Matrix4d& world) {
    const std::string where = fmt::format("meshes[{}]", m);
    const json& mesh = element("meshes", m, where);
    const json* primitives = find(mesh, "primitives");
    if (!primitives || !primitives->is_array()) fail(where + ": expected 'primitives' to be an array");
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const std::string at = fmt::format("{}.primitives[{}]", where, p);
      const std::size_t mode = natural(primitive, "mode", at, 4);
      if (mode <= 3) {  // points, lines, line loops, line strips: no surface
        ++skipped_primitives_;
        continue;
      }
      if (mode > 6) fail(fmt::format("{}: unknown mode {}", at, mode));
      const json* attributes = find(primitive, "attributes");
      if (!attributes || !find(*attributes, "POSITION")) fail(at + " has no POSITION attribute");
      const std::vector<Vec3> local = read_positions(natural(*attributes, "POSITION", at));
      const std::size_t material = primitive_material(primitive, at);
      std::vector<Colour> colours = read_colours(*attributes, local.size(), material, at);
      const std::vector<TexCoord> uv = read_texture_coordinates(*attributes, local.size(), material, at);
      std::vector<std::uint32_t> corners;
      if (find(primitive, "indices")) {
        corners = read_indices(natural(primitive, "indices", at), local.size());
      } else {
        corners.resize(local.size());
        for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = static_cast<std::uint32_t>(k);
      }
      if (mode == 4 && corners.size() % 3 != 0)
        fail(fmt::format("{}: {} indices, expected a multiple of 3", at, corners.size()));
      const std::size_t triangles = mode == 4             ? corners.size() / 3
                                    : corners.size() >= 3 ? corners.size() - 2
                                                          : 0;
      // Every placement copies the primitive: a node tree can place one mesh many times.
      require_memory("reading " + path(),
                     double(positions_.size() + local.size()) * sizeof(Vec3) +
                         double(triangles_.size() + triangles) * sizeof(Triangle),
                     "the placed triangles");
      const std::size_t base = positions_.size();
      if (base + local.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        fail("more vertices than a mesh can index");
      }
      for (const Vec3& q : local) positions_.push_back((world * q.homogeneous()).head<3>());
      if (any_vertex_colour_) {  // white before the first COLOR_0 and where a primitive has none
        vertex_colours_.resize(base, Colour::Constant(255));
        if (colours.empty()) colours.resize(local.size(), Colour::Constant(255));
        vertex_colours_.insert(vertex_colours_.end(), colours.begin(), colours.end());
      }
      for (std::size_t t = 0; t < triangles; ++t) {
        std::uint32_t a, b, c;
        if (mode == 4)
          a = corners[3 * t], b = corners[3 * t + 1], c = corners[3 * t + 2];
        else if (mode == 5)
          a = corners[t], b = corners[t + 1 + t % 2], c = corners[t + 2 - t % 2];  // strip
        else
          a = corners[0], b = corners[t + 1], c = corners[t + 2];  // fan
        if (a == b || b == c || a == c) {
          ++dropped_faces_;
          continue;
        }
        triangles_.push_back(
            {static_cast<int>(base + a), static_cast<int>(base + b), static_cast<int>(base + c)});
        if (any_material_colour_) {  // the default material before the first coloured one
          align_material_arrays(triangles_.size() - 1);
          face_material_.push_back(static_cast<int>(material));
          for (const std::uint32_t corner : {a, b, c})
            corner_uv_.push_back(uv.empty() ? TexCoord::Zero() : uv[corner]);
        }
      }
    }
  }

  // Material 0 (glTF's default) and no texture coordinates for the first `triangles` triangles
  // where nothing was recorded: only a coloured model keeps per-triangle colour data.
  void align_material_arrays(std::size_t triangles) {
    face_material_.resize(triangles, 0);
    corner_uv_.resize(3 * triangles, TexCoord::Zero());
  }

  // COLOR_0 in sRGB code values (glTF's colours are linear: the sRGB transfer function encodes
  // them); empty where the primitive has none. On an untextured material whose factor is F (in
  // code values), a colour c becomes 255 code(f c) / F, so that the rule's product of code values
  // gives glTF's code(f c) at each vertex.
  std::vector<Colour> read_colours(const json& attributes, std::size_t vertices, std::size_t material,
                                   const std::string& at) {
    if (!find(attributes, "COLOR_0")) return {};
    const std::size_t index = natural(attributes, "COLOR_0", at);
    const Accessor a = accessor(index, "VEC3|VEC4", "COLOR_0");
    const std::string where = fmt::format("accessors[{}] (COLOR_0)", index);
    if (a.count != vertices) fail(fmt::format("{}: {} colours for {} vertices", where, a.count, vertices));
    std::vector<Colour> out(vertices);
    for (std::size_t k = 0; k < vertices; ++k) {
      double rgb[3];
      read_floats(a, k, 3, rgb, where);
      for (int c = 0; c < 3; ++c) {
        if (!(rgb[c] >= 0 && rgb[c] <= 1)) {
          fail(fmt::format("{}: colour {} has {}; expected 0 to 1", where, k, rgb[c]));
        }
        const double factor = material_linear_factor_[material][c];
        const double code = materials_[material].factor[c];
        out[k][c] = static_cast<float>(materials_[material].texture || code == 255 ? srgb_code(rgb[c])
                                       : code > 0 ? 255 * srgb_code(factor * rgb[c]) / code
                                                  : 0.0);
      }
    }
    any_vertex_colour_ = true;
    return out;
  }

  // TEXCOORD_0, where the primitive's material has a texture (glTF's: u right, v down).
  std::vector<TexCoord> read_texture_coordinates(const json& attributes, std::size_t vertices,
                                                 std::size_t material, const std::string& at) {
    if (!materials_[material].texture) return {};
    if (!find(attributes, "TEXCOORD_0")) {
      fail(fmt::format("{}: its material has a baseColorTexture but it has no TEXCOORD_0", at));
    }
    const std::size_t index = natural(attributes, "TEXCOORD_0", at);
    const Accessor a = accessor(index, "VEC2", "TEXCOORD_0");
    const std::string where = fmt::format("accessors[{}] (TEXCOORD_0)", index);
    if (a.count != vertices)
      fail(fmt::format("{}: {} coordinates for {} vertices", where, a.count, vertices));
    std::vector<TexCoord> out(vertices);
    for (std::size_t k = 0; k < vertices; ++k) {
      read_floats(a, k, 2, out[k].data(), where);
      if (!out[k].allFinite()) fail(fmt::format("{}: coordinate {} is not finite", where, k));
    }
    return out;
  }

  // Our index of the primitive's material: glTF's default (white, untextured) where it names
  // none. A material's base colour is its colour: baseColorFactor times baseColorTexture, which
  // glTF multiplies in linear light. Untextured, the factor is encoded to code values; textured,
  // it is baked into a copy of the texture texel by texel in linear light (rounded to 8 bits), so
  // that at texel centres the colour is glTF's; the factor is then white.
  std::size_t primitive_material(const json& primitive, const std::string& at) {
    if (materials_.empty()) {
      materials_.emplace_back().name = "glTF default";
      material_linear_factor_.push_back(Vec3::Ones());
    }
    if (!find(primitive, "material")) return 0;
    const std::size_t index = natural(primitive, "material", at);
    if (const auto known = material_index_.find(index); known != material_index_.end()) return known->second;
    const std::string where = fmt::format("materials[{}]", index);
    const json& m = element("materials", index, at);
    Material material;
    material.name =
        find(m, "name") && find(m, "name")->is_string() ? find(m, "name")->get<std::string>() : where;
    Vec3 linear_factor = Vec3::Ones();
    if (const json* pbr = find(m, "pbrMetallicRoughness")) {
      if (const json* factor = find(*pbr, "baseColorFactor")) {
        if (!factor->is_array() || factor->size() != 4)
          fail(where + ": expected baseColorFactor of 4 numbers");
        for (int c = 0; c < 3; ++c) {
          const json& x = (*factor)[c];
          if (!x.is_number() || !(x.get<double>() >= 0 && x.get<double>() <= 1)) {
            fail(fmt::format("{}: baseColorFactor holds {}; expected 0 to 1", where, x.dump()));
          }
          linear_factor[c] = x.get<double>();
          material.factor[c] = static_cast<float>(srgb_code(linear_factor[c]));
        }
        any_material_colour_ = true;
      }
      if (const json* info = find(*pbr, "baseColorTexture")) {
        const std::string info_where = where + ".baseColorTexture";
        if (natural(*info, "texCoord", info_where, 0) != 0) fail(info_where + ": only texCoord 0 is read");
        if (const json* extensions = find(*info, "extensions");
            extensions && find(*extensions, "KHR_texture_transform")) {
          fail(info_where + ": KHR_texture_transform is not read; bake the transform into TEXCOORD_0");
        }
        read_texture(natural(*info, "index", info_where), material);
        if (linear_factor != Vec3::Ones()) material.texture = with_factor(*material.texture, linear_factor);
        material.factor = Colour::Constant(255);
        any_material_colour_ = true;
      }
    }
    materials_.push_back(std::move(material));
    material_linear_factor_.push_back(linear_factor);
    return material_index_[index] = materials_.size() - 1;
  }

  // `texture` with every texel multiplied by `factor` in linear light, as glTF multiplies them.
  static std::shared_ptr<const Texture> with_factor(const Texture& texture, const Vec3& factor) {
    auto baked = std::make_shared<Texture>(texture);
    for (std::size_t i = 0; i < baked->rgb.size(); ++i) {
      const double linear = srgb_linear(baked->rgb[i]) * factor[static_cast<int>(i % 3)];
      baked->rgb[i] = static_cast<std::uint8_t>(std::lround(std::clamp(srgb_code(linear), 0.0, 255.0)));
    }
    return baked;
  }

  // textures[index]: its image (decoded once however many materials use it) and its sampler.
  void read_texture(std::size_t index, Material& material) {
    const std::string where = fmt::format("textures[{}]", index);
    const json& t = element("textures", index, where);
    if (!find(t, "source"))
      fail(where + " has no source image (a texture extension this reader does not read?)");
    const std::size_t source = natural(t, "source", where);
    if (!images_[source]) images_[source] = std::make_shared<const Texture>(read_image(source));
    material.texture = images_[source];
    if (find(t, "sampler")) {
      const std::size_t s = natural(t, "sampler", where);
      const std::string sampler_where = fmt::format("samplers[{}]", s);
      const json& sampler = element("samplers", s, where);
      const auto wrap = [&](const char* key) {
        const std::size_t mode = natural(sampler, key, sampler_where, 10497);
        if (mode == 10497) return Wrap::Repeat;
        if (mode == 33071) return Wrap::ClampToEdge;
        if (mode == 33648) return Wrap::MirroredRepeat;
        fail(fmt::format("{}: unknown {} {}", sampler_where, key, mode));
      };
      material.sampler.wrap_s = wrap("wrapS");
      material.sampler.wrap_t = wrap("wrapT");
      const std::size_t filter = natural(sampler, "magFilter", sampler_where, 9729);
      if (filter != 9728 && filter != 9729)
        fail(fmt::format("{}: unknown magFilter {}", sampler_where, filter));
      material.sampler.filter = filter == 9728 ? Filter::Nearest : Filter::Linear;
    }
  }

  // images[index] decoded: a file beside the .gltf, a data URI, or a buffer view (a GLB's).
  Texture read_image(std::size_t index) {
    const std::string where = fmt::format("images[{}]", index);
    const json& image = element("images", index, where);
    const std::string source = fmt::format("{} {}", path(), where);
    try {
      if (const json* uri = find(image, "uri")) {
        if (!uri->is_string()) fail(where + ": expected 'uri' to be a string");
        const std::string text = uri->get<std::string>();
        if (const std::optional<std::string> decoded = data_uri_bytes(text, where)) {
          return decode_texture(*decoded, source);
        }
        return ::roving::read_texture(resolve_reference(path(), text, where + "'s uri"));
      }
      return decode_texture(view_bytes(natural(image, "bufferView", where), where), source);
    } catch (const Error& e) {
      const std::string message = e.what();
      if (message.rfind(path() + ":", 0) == 0) throw;
      fail(fmt::format("{}: {}", where, message));
    }
  }

  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> parent_;
  bool nodes_present_ = false;
  std::size_t placed_nodes_ = 0;
  std::vector<Vec3> positions_;
  std::vector<Triangle> triangles_;
  std::size_t dropped_faces_ = 0, skipped_primitives_ = 0;
  // Colour, once a model has some: per vertex (white where a primitive has no COLOR_0), per
  // triangle its material and its corners' texture coordinates; glTF's materials as read, by
  // their index, and its images.
  std::vector<Colour> vertex_colours_;
  std::vector<Material> materials_;
  std::vector<Vec3> material_linear_factor_;  // baseColorFactor as given, per material
  std::vector<int> face_material_;
  std::vector<TexCoord> corner_uv_;
  std::map<std::size_t, std::size_t> material_index_;
  std::map<std::size_t, std::shared_ptr<const Texture>> images_;
  bool any_vertex_colour_ = false, any_material_colour_ = false;
};

}  // namespace

LoadedMesh read_gltf(const std::string& path) {
  return GltfReader(path).read();
}

}  // namespace roving
