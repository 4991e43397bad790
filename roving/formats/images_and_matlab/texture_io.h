// Texture images: PNG through libpng, JPEG through libjpeg-turbo, 8-bit RGB code values as stored
// (no gamma or colour-profile conversion: MPEG's metrics compare the stored values).
#pragma once

#include <string>
#include <string_view>

#include "roving/core/texture.h"

namespace roving {

// The largest side and pixel count a texture may declare (GPUs stop at 16384 or 32768 a side);
// checked from the header, before any pixel is allocated.
constexpr int kMaxTextureSide = 32768;
constexpr long long kMaxTexturePixels = 1LL << 28;

// Reads a .png or .jpg/.jpeg file (chosen by its first bytes, not its name). Grey images become
// grey RGB, palettes are expanded, 16-bit channels rounded to 8 bits, alpha ignored. Throws
// roving::Error naming the file for anything else: a missing or empty file, another format, a
// corrupt or truncated stream (a JPEG's warnings included), a declared size beyond the limits or this
// machine's memory.
Texture read_texture(const std::string& path);
// The same from bytes already in memory (a glTF's embedded image); `source` names them in messages.
Texture decode_texture(std::string_view bytes, const std::string& source);

// Writes `texture` whole or not at all (AtomicFile): PNG when `jpeg_quality` is 0, else baseline
// JPEG at that quality (1-100, 4:2:0 as libjpeg's default). Throws roving::Error naming the file.
void write_texture(const Texture& texture, const std::string& path, int jpeg_quality = 0);

}  // namespace roving
