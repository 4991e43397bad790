// Strict Wavefront OBJ reader. OpenMesh's reader parses through iostreams (87% of a bunny load:
// 0.15 s of a 0.25 s budget) and skips malformed records without a word; this one parses with
// std::from_chars and names the line of the first bad record.
#include "roving/formats/meshes/obj_reader.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <string_view>

#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/mtl_reader.h"
#include "roving/formats/meshes/obj_records.h"
#include "roving/core/error.h"

namespace roving {

LoadedMesh read_obj(const std::string& path) {
  const FileBytes file(path, "a .obj mesh");
  LineCursor lines(file.bytes());

  std::vector<Vec3> positions;
  std::vector<Colour> colours;  // one per `v` that gave one
  std::vector<TexCoord> coordinates;
  std::vector<Triangle> triangles;
  std::vector<int> corner_texcoord;  // three per triangle; -1: none given
  std::vector<int> face_material;    // one per triangle; -1: before any usemtl
  std::map<std::string, Material> library;
  TextureCache textures;
  std::vector<Material> used;  // the materials faces name, in order of first use
  std::map<std::string, int> used_index;
  int material = -1;
  // A material library or a texture that is not there: the geometry is read without materials, with
  // a warning (as MeshLab and Open3D read it); one that is there but malformed is still an error.
  bool materials_dropped = false;
  std::size_t first_unmaterialled_line = 0, first_textured_without_uv_line = 0;

  LoadedMesh loaded;
  std::vector<int> corners, corner_uv;
  const obj::Fail fail = obj::line_error(path, lines);
  std::string_view line;
  while (lines.next_line(line)) {
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "v") {
      Vec3 position;
      double rgb[3];
      const bool coloured = obj::parse_vertex(rest, position, rgb, fail);
      positions.push_back(position);
      if (coloured) {
        for (const double c : rgb) {
          if (!(c >= 0 && c <= 1)) {
            throw fail(fmt::format("vertex colour ({}, {}, {}); expected fractions within [0, 1]", rgb[0],
                                   rgb[1], rgb[2]));
          }
        }
        if (colours.size() + 1 != positions.size()) {
          throw fail(
              fmt::format("vertex {} has a colour but {} earlier vertices have none; expected colours on "
                          "every vertex or on none",
                          positions.size(), positions.size() - 1 - colours.size()));
        }
        colours.emplace_back(float(255 * rgb[0]), float(255 * rgb[1]), float(255 * rgb[2]));
      }
    } else if (keyword == "vt") {
      double uv[2];
      obj::parse_texture_coordinate(rest, uv, fail);
      coordinates.emplace_back(uv[0], 1 - uv[1]);  // OBJ's v runs up from the image's bottom row
    } else if (keyword == "f") {
      obj::parse_face(rest, static_cast<long long>(positions.size()), static_cast<long long>(coordinates.size()),
                      corners, corner_uv, fail);
      if (obj::repeats_a_vertex(corners)) {
        ++loaded.dropped_repeated_vertex_faces;
        continue;
      }
      if (material < 0 && !first_unmaterialled_line) first_unmaterialled_line = lines.line_number();
      const bool needs_uv = material >= 0 && used[material].texture;
      for (const int uv : corner_uv) {
        if (needs_uv && uv < 0 && !first_textured_without_uv_line) {
          first_textured_without_uv_line = lines.line_number();
        }
      }
      if (corners.size() > 3) ++loaded.triangulated_polygons;
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        triangles.push_back({corners[0], corners[i], corners[i + 1]});
        corner_texcoord.insert(corner_texcoord.end(), {corner_uv[0], corner_uv[i], corner_uv[i + 1]});
        face_material.push_back(material);
      }
    } else if (keyword == "mtllib") {
      for (std::string_view name = next_token(rest); !name.empty(); name = next_token(rest)) {
        try {
          const std::string library_path = resolve_reference(path, std::string(name), "mtllib");
          std::error_code error;
          if (!materials_required() && !std::filesystem::exists(library_path, error)) {
            loaded.warnings.push_back(fmt::format("{}:{}: mtllib {}: no such file '{}'; measured without its "
                                                  "materials (no colour from them)",
                                                  path, lines.line_number(), roving::quoted(name), library_path));
            materials_dropped = true;
            continue;
          }
          std::vector<std::string> missing;
          read_mtl(library_path, library, textures, missing);
          for (const std::string& texture : missing) {
            loaded.warnings.push_back(fmt::format("{}:{}: {}; measured without its materials (no colour from them)",
                                                  path, lines.line_number(), texture));
          }
          if (!missing.empty()) materials_dropped = true;
        } catch (const Error& e) {
          throw fail(e.what());  // names the OBJ and its line, then the library's own file and line
        }
      }
    } else if (keyword == "usemtl" && !materials_dropped) {
      const std::string name(next_token(rest));
      const auto found = library.find(name);
      if (found == library.end()) {
        throw fail(fmt::format("usemtl {}: no such material in the libraries 'mtllib' named before it",
                               roving::quoted(name)));
      }
      const auto [at, inserted] = used_index.emplace(name, static_cast<int>(used.size()));
      if (inserted) used.push_back(found->second);
      material = at->second;
    }
    // Everything else (vn, g, o, s, l, #...) carries nothing we use.
  }
  loaded.path = path;
  loaded.mesh = TriangleMesh(std::move(positions), std::move(triangles), path);
  if (!colours.empty()) {
    if (colours.size() != loaded.mesh.vertex_count()) {
      throw Error(fmt::format("{}: {} of {} vertices have a colour; expected every vertex or none", path,
                              colours.size(), loaded.mesh.vertex_count()));
    }
    loaded.mesh.set_vertex_colours(std::move(colours), path);
  }
  if (used.empty() || materials_dropped) return loaded;
  if (first_unmaterialled_line) {
    throw Error(
        fmt::format("{}:{}: face has no material ('usemtl') while others have one; expected a material "
                    "on every face or on none",
                    path, first_unmaterialled_line));
  }
  if (first_textured_without_uv_line) {
    throw Error(
        fmt::format("{}:{}: face has a textured material but a corner without a texture coordinate "
                    "(expected v/vt)",
                    path, first_textured_without_uv_line));
  }
  TextureMapping mapping;
  mapping.materials = std::move(used);
  mapping.face_material = std::move(face_material);
  mapping.corner_uv.reserve(corner_texcoord.size());
  for (const int uv : corner_texcoord)
    mapping.corner_uv.push_back(uv < 0 ? TexCoord::Zero() : coordinates[uv]);
  loaded.mesh.set_texture_mapping(std::move(mapping), path);
  return loaded;
}

}  // namespace roving
