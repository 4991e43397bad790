// Wavefront MTL material libraries: the diffuse colour (Kd) and its texture (map_Kd).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roving/core/texture.h"

namespace roving {

// Textures already read, by resolved path, so that materials and libraries sharing one decode it once.
using TextureCache = std::map<std::string, std::shared_ptr<const Texture>>;

// Reads the materials of `path` into `materials` (a later definition of a name replaces an earlier
// one, as in the viewers). Kd is taken as sRGB fractions (code values / 255, as every OBJ viewer
// displays it); a material without Kd is white. map_Kd's image is read through `textures`; of its
// options only -clamp is honoured (on: clamp to edge; the default repeats). A texture file that is
// not there is named in `missing_textures` (the caller measures the geometry without the
// materials' colour, as MeshLab and Open3D read it). Throws roving::Error naming the file and line
// for a malformed or out-of-range Kd, an option we do not apply, or a texture that is there but
// unreadable.
void read_mtl(const std::string& path, std::map<std::string, Material>& materials, TextureCache& textures,
              std::vector<std::string>& missing_textures);

// require_materials(true) (the CLI's --strict-materials): a material library or texture that is
// not there is an error naming it, not a warning (read_mtl and the OBJ reader ask
// materials_required()).
void require_materials(bool required);
bool materials_required();

}  // namespace roving
