// Strict MTL reader: only what decides a surface's colour, everything else skipped.
#include "roving/formats/meshes/mtl_reader.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string_view>

#include "roving/core/error.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/images_and_matlab/texture_io.h"

namespace roving {
namespace {

bool strict_materials = false;

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
    text.remove_suffix(1);
  return text;
}

}  // namespace

void require_materials(bool required) {
  strict_materials = required;
}

bool materials_required() {
  return strict_materials;
}

void read_mtl(const std::string& path, std::map<std::string, Material>& materials, TextureCache& textures,
              std::vector<std::string>& missing_textures) {
  const FileBytes file(path, "an .mtl material library");
  LineCursor lines(file.bytes());
  Material* current = nullptr;
  std::string_view line;
  while (lines.next_line(line)) {
    const auto fail = [&](const std::string& what) {
      return Error(fmt::format("{}:{}: {}", path, lines.line_number(), what));
    };
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword == "newmtl") {
      const std::string name(trimmed(rest));
      if (name.empty()) throw fail("expected a material name after 'newmtl'");
      current = &materials[name];
      *current = Material();
      current->name = name;
      continue;
    }
    if (keyword != "Kd" && keyword != "map_Kd") continue;  // Ka, Ks, Ns, d, illum, other maps: no colour
    if (!current) throw fail(fmt::format("'{}' before any 'newmtl'", keyword));
    if (keyword == "Kd") {
      double kd[3];
      for (double& k : kd) {
        const std::string_view token = next_token(rest);
        if (!parse_number(token, k) || !(k >= 0 && k <= 1)) {
          throw fail(
              fmt::format("expected 3 numbers within [0, 1] after 'Kd' (RGB; spectral and xyz are not "
                          "supported), found {}",
                          quoted(token)));
        }
      }
      current->factor = Colour(float(255 * kd[0]), float(255 * kd[1]), float(255 * kd[2]));
      continue;
    }
    // map_Kd [-option value...] file: the file is the rest of the line, spaces and all.
    Sampler sampler;
    rest = trimmed(rest);
    while (!rest.empty() && rest.front() == '-') {
      std::string_view probe = rest;
      const std::string_view option = next_token(probe);
      if (option != "-clamp") {
        throw fail(
            fmt::format("map_Kd option {} is not supported (only -clamp is); remove it or bake it into "
                        "the texture",
                        quoted(option)));
      }
      const std::string_view value = next_token(probe);
      if (value != "on" && value != "off")
        throw fail(fmt::format("expected on or off after -clamp, found {}", quoted(value)));
      sampler.wrap_s = sampler.wrap_t = value == "on" ? Wrap::ClampToEdge : Wrap::Repeat;
      rest = trimmed(probe);
    }
    if (rest.empty()) throw fail("expected a texture file after 'map_Kd'");
    const std::string texture_path = resolve_reference(path, std::string(rest), "map_Kd");
    std::error_code error;
    if (!strict_materials && !std::filesystem::exists(texture_path, error)) {
      missing_textures.push_back(fmt::format("{}:{}: map_Kd: no such file '{}'", path, lines.line_number(), texture_path));
      continue;
    }
    std::shared_ptr<const Texture>& texture = textures[texture_path];
    try {
      if (!texture) texture = std::make_shared<const Texture>(read_texture(texture_path));
    } catch (const Error& e) {
      textures.erase(texture_path);
      throw fail(fmt::format("map_Kd: {}", e.what()));
    }
    current->texture = texture;
    current->sampler = sampler;
  }
}

}  // namespace roving
