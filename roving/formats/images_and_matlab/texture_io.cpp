// PNG and JPEG decoding for textures. Both libraries report errors by longjmp; each decoder keeps
// its setjmp frame free of C++ objects that own memory, so a jump leaks nothing and skips no
// destructor that matters.
#include "roving/formats/images_and_matlab/texture_io.h"

#include <fmt/format.h>
#include <jpeglib.h>
#include <png.h>
#include <stdio.h>  // jpeglib.h needs FILE and size_t declared first

#include <csetjmp>
#include <cstring>

#include "roving/core/error.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"

namespace roving {
namespace {

void check_size(const std::string& path, long long width, long long height) {
  if (width < 1 || height < 1 || width > kMaxTextureSide || height > kMaxTextureSide ||
      width * height > kMaxTexturePixels) {
    throw Error(
        fmt::format("{}: the image declares {} x {} pixels; expected 1 to {} a side and at most {} "
                    "pixels",
                    path, width, height, kMaxTextureSide, kMaxTexturePixels));
  }
  require_memory("reading a texture", 3.0 * width * height, path);
}

// ---- PNG ----

struct PngInput {
  std::string_view bytes;
  std::size_t at = 8;  // after the signature, which png_sig_cmp checked
  char message[200] = "";
};

void png_read_bytes(png_structp png, png_bytep out, png_size_t count) {
  auto* input = static_cast<PngInput*>(png_get_io_ptr(png));
  if (count > input->bytes.size() - input->at) png_error(png, "the file ends inside the image");
  std::memcpy(out, input->bytes.data() + input->at, count);
  input->at += count;
}

void png_fail(png_structp png, png_const_charp message) {
  auto* input = static_cast<PngInput*>(png_get_io_ptr(png));
  std::snprintf(input->message, sizeof input->message, "%s", message);
  png_longjmp(png, 1);
}

void png_ignore_warning(png_structp, png_const_charp) {}

// Decodes into `texture` (its size set first by `on_header`); false with input.message on error.
template <typename OnHeader>
bool decode_png(PngInput& input, Texture& texture, OnHeader on_header) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::snprintf(input.message, sizeof input.message, "out of memory");
    return false;
  }
  png_set_read_fn(png, &input, png_read_bytes);
  png_set_error_fn(png, &input, png_fail, png_ignore_warning);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, kMaxTextureSide, kMaxTextureSide);
  png_set_chunk_malloc_max(png, 64u << 20);
  png_read_info(png, info);
  // Stored values as 8-bit RGB: no png_set_gamma or colour management, on purpose.
  png_set_expand(png);  // palette, low-bit grey and tRNS to full channels
  png_set_scale_16(png);
  png_set_gray_to_rgb(png);
  png_set_strip_alpha(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != 3 * png_get_image_width(png, info)) {
    png_error(png, "unexpected row layout after conversion to 8-bit RGB");
  }
  if (!on_header(png_get_image_width(png, info), png_get_image_height(png, info))) {
    png_error(png, "image too large");  // on_header has already said why, by throwing after return
  }
  for (int pass = 0; pass < passes; ++pass) {
    for (int row = 0; row < texture.height; ++row) {
      png_read_row(png, &texture.rgb[std::size_t(row) * texture.width * 3], nullptr);
    }
  }
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

Texture read_png(const std::string& path, std::string_view bytes) {
  Texture texture;
  texture.source = path;
  PngInput input{bytes};
  std::string size_error;
  const bool ok = decode_png(input, texture, [&](png_uint_32 width, png_uint_32 height) {
    try {
      check_size(path, width, height);
    } catch (const Error& e) {
      size_error = e.what();
      return false;
    }
    texture.width = static_cast<int>(width);
    texture.height = static_cast<int>(height);
    texture.rgb.resize(std::size_t(width) * height * 3);
    return true;
  });
  if (!size_error.empty()) throw Error(size_error);
  if (!ok) throw Error(fmt::format("{}: not a readable PNG image: {}", path, input.message));
  return texture;
}

// ---- JPEG ----

struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = "";
};

void jpeg_fail(j_common_ptr jpeg) {
  auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
  (*jpeg->err->format_message)(jpeg, errors->message);
  std::longjmp(errors->jump, 1);
}

// libjpeg only warns of a truncated or corrupt stream and goes on with grey or repeated data: the
// strict reading every other file gets makes each warning an error.
void jpeg_warning_fails(j_common_ptr jpeg, int level) {
  if (level < 0) jpeg_fail(jpeg);
}

// Reads the header into `width` and `height`, then, when `texture` is sized, the pixels.
bool decode_jpeg(std::string_view bytes, JpegErrors& errors, Texture* texture, long long& width,
                 long long& height) {
  jpeg_decompress_struct jpeg;
  jpeg.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_fail;
  errors.manager.emit_message = jpeg_warning_fails;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&jpeg);
    return false;
  }
  jpeg_create_decompress(&jpeg);
  jpeg_mem_src(&jpeg, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  jpeg_read_header(&jpeg, TRUE);
  width = jpeg.image_width;
  height = jpeg.image_height;
  if (texture) {
    if (jpeg.jpeg_color_space == JCS_CMYK || jpeg.jpeg_color_space == JCS_YCCK) {
      std::snprintf(errors.message, sizeof errors.message,
                    "CMYK images are not supported; expected RGB or grey");
      jpeg_destroy_decompress(&jpeg);
      return false;
    }
    jpeg.out_color_space = JCS_RGB;
    jpeg_start_decompress(&jpeg);
    while (jpeg.output_scanline < jpeg.output_height) {
      JSAMPROW row = &texture->rgb[std::size_t(jpeg.output_scanline) * texture->width * 3];
      jpeg_read_scanlines(&jpeg, &row, 1);
    }
    jpeg_finish_decompress(&jpeg);
  }
  jpeg_destroy_decompress(&jpeg);
  return true;
}

Texture read_jpeg(const std::string& path, std::string_view bytes) {
  JpegErrors errors;
  long long width = 0, height = 0;
  const auto fail = [&] {
    return Error(fmt::format("{}: not a readable JPEG image: {}", path, errors.message));
  };
  if (!decode_jpeg(bytes, errors, nullptr, width, height)) throw fail();
  check_size(path, width, height);
  Texture texture;
  texture.source = path;
  texture.width = static_cast<int>(width);
  texture.height = static_cast<int>(height);
  texture.rgb.resize(std::size_t(width) * height * 3);
  if (!decode_jpeg(bytes, errors, &texture, width, height)) throw fail();
  return texture;
}

// Both writers run inside a setjmp frame with only C data in it; false on the library's error.
bool encode_png(const Texture& texture, std::FILE* out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, texture.width, texture.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int row = 0; row < texture.height; ++row) {
    png_write_row(png, &texture.rgb[std::size_t(row) * texture.width * 3]);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

bool encode_jpeg(const Texture& texture, int quality, std::FILE* out, JpegErrors& errors) {
  jpeg_compress_struct jpeg;
  jpeg.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_fail;
  if (setjmp(errors.jump)) {
    jpeg_destroy_compress(&jpeg);
    return false;
  }
  jpeg_create_compress(&jpeg);
  jpeg_stdio_dest(&jpeg, out);
  jpeg.image_width = texture.width;
  jpeg.image_height = texture.height;
  jpeg.input_components = 3;
  jpeg.in_color_space = JCS_RGB;
  jpeg_set_defaults(&jpeg);
  jpeg_set_quality(&jpeg, quality, TRUE);
  jpeg_start_compress(&jpeg, TRUE);
  while (jpeg.next_scanline < jpeg.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(&texture.rgb[std::size_t(jpeg.next_scanline) * texture.width * 3]);
    jpeg_write_scanlines(&jpeg, &row, 1);
  }
  jpeg_finish_compress(&jpeg);
  jpeg_destroy_compress(&jpeg);
  return true;
}

}  // namespace

void write_texture(const Texture& texture, const std::string& path, int jpeg_quality) {
  if (jpeg_quality < 0 || jpeg_quality > 100) {
    throw Error(fmt::format("{}: JPEG quality {}; expected 1 to 100 (0 writes PNG)", path, jpeg_quality));
  }
  AtomicFile file(path);
  JpegErrors errors;
  const bool ok = jpeg_quality == 0 ? encode_png(texture, file.stream())
                                    : encode_jpeg(texture, jpeg_quality, file.stream(), errors);
  if (!ok)
    throw Error(
        fmt::format("{}: cannot encode the image{}{}", path, *errors.message ? ": " : "", errors.message));
  file.commit();
}

Texture read_texture(const std::string& path) {
  const FileBytes file(path, "a PNG or JPEG texture");
  return decode_texture(file.bytes(), path);
}

Texture decode_texture(std::string_view bytes, const std::string& path) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() >= 8 && png_sig_cmp(data, 0, 8) == 0) return read_png(path, bytes);
  if (bytes.size() >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF)
    return read_jpeg(path, bytes);
  throw Error(fmt::format("{}: not a texture image; expected a PNG or JPEG file (by its first bytes)", path));
}

}  // namespace roving
