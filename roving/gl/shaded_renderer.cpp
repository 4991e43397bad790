// Colour renderings on OpenGL 4.5 core: an RGBA8 + depth FBO, flat colours, a headlight-style
// light, supersampled 3x3 and box-filtered on the CPU.
#include "roving/gl/shaded_renderer.h"

#include <fmt/format.h>

#include "gl_api.h"
#include "gl_context.h"
#include "gl_program.h"
#include "roving/core/error.h"

namespace roving {
namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 colour;
uniform vec3 centre;          // camera centre, same frame as position
uniform vec3 right_scaled;    // right / half_width
uniform vec3 up_scaled;       // up / half_height
uniform vec3 forward_scaled;  // forward / (2 half_depth)
uniform vec3 light;           // unit vector towards the light
uniform float point_size;
out vec3 shaded;
void main() {
  vec3 p = position - centre;
  gl_Position = vec4(dot(p, right_scaled), dot(p, up_scaled), 2.0 * (dot(p, forward_scaled) + 0.5) - 1.0, 1.0);
  gl_PointSize = point_size;
  // Both sides lit alike: a reference's orientation is not what the picture is about.
  shaded = colour * (0.35 + 0.65 * abs(dot(normalize(normal), light)));
}
)";

constexpr const char* kFragmentShader = R"(#version 450 core
in vec3 shaded;
out vec4 colour;
void main() { colour = vec4(shaded, 1.0); }
)";

constexpr int kSupersampling = 3;

}  // namespace

std::vector<RgbImage> render_shaded(GlBackend backend, const ColouredSurface& surface,
                                    const std::vector<OrthoCamera>& cameras, int width, int height) {
  const auto context = gl::make_context(backend);
  gl::Api gl;
  gl.load([&](const char* name) { return context->proc_address(name); }, context->platform());
  const std::string platform = context->platform();
  GLint max_size = 0;
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  const int w = width * kSupersampling, h = height * kSupersampling;
  if (width < 1 || height < 1 || w > max_size || h > max_size) {
    throw Error(fmt::format("gl ({}): a {} x {} picture is outside 1..{} pixels a side", platform, width,
                            height, max_size / kSupersampling));
  }
  const GLuint program = gl::link_program(gl, platform, "shaded", kVertexShader, kFragmentShader);

  // Positions relative to their box's centre, so float keeps ~1e-7 of the model's size.
  BoundingBox box;
  for (const Vec3& p : surface.positions) box.extend(p);
  const Vec3 origin = surface.positions.empty() ? Vec3::Zero() : box.centre();
  std::vector<float> attributes;
  attributes.reserve(9 * surface.positions.size());
  for (std::size_t k = 0; k < surface.positions.size(); ++k) {
    const Vec3 p = surface.positions[k] - origin;
    const Vec3& n = surface.normals[k];
    const Rgb& c = surface.colours[k];
    attributes.insert(attributes.end(), {float(p.x()), float(p.y()), float(p.z()), float(n.x()), float(n.y()),
                                         float(n.z()), c[0] / 255.f, c[1] / 255.f, c[2] / 255.f});
  }
  GLuint vao = 0, buffer = 0, framebuffer = 0, buffers[2] = {0, 0};
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.GenBuffers(1, &buffer);
  gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
  gl.BufferData(GL_ARRAY_BUFFER, attributes.size() * sizeof(float), attributes.data(), GL_STATIC_DRAW);
  for (GLuint a = 0; a < 3; ++a) {
    gl.VertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float),
                           reinterpret_cast<void*>(3 * a * sizeof(float)));
    gl.EnableVertexAttribArray(a);
  }
  gl.GenFramebuffers(1, &framebuffer);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  gl.GenRenderbuffers(2, buffers);
  gl.BindRenderbuffer(GL_RENDERBUFFER, buffers[0]);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, buffers[0]);
  gl.BindRenderbuffer(GL_RENDERBUFFER, buffers[1]);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, buffers[1]);
  gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw Error(fmt::format("gl ({}): a {} x {} colour framebuffer is incomplete", platform, w, h));
  }
  gl.Viewport(0, 0, w, h);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.Enable(GL_PROGRAM_POINT_SIZE);
  gl.UseProgram(program);
  gl.Uniform1f(gl.GetUniformLocation(program, "point_size"), float(2 * kSupersampling));
  const auto uniform3 = [&](const char* name, const Vec3& v) {
    gl.Uniform3f(gl.GetUniformLocation(program, name), float(v.x()), float(v.y()), float(v.z()));
  };

  std::vector<RgbImage> images;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(4) * w * h);
  for (const OrthoCamera& camera : cameras) {
    uniform3("centre", camera.centre - origin);
    uniform3("right_scaled", camera.right / camera.half_width);
    uniform3("up_scaled", camera.up / camera.half_height);
    uniform3("forward_scaled", camera.forward / (2 * camera.half_depth));
    uniform3("light", (-camera.forward + 0.5 * camera.up - 0.4 * camera.right).normalized());
    gl.ClearColor(1, 1, 1, 1);
    gl.ClearDepth(1.0);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.DrawArrays(surface.points ? GL_POINTS : GL_TRIANGLES, 0,
                  static_cast<GLsizei>(surface.positions.size()));
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    gl::check_error(gl, platform, "rendering a picture");
    RgbImage image{width, height, std::vector<unsigned char>(static_cast<std::size_t>(3) * width * height)};
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        for (int c = 0; c < 3; ++c) {
          int sum = 0;
          for (int dy = 0; dy < kSupersampling; ++dy) {
            for (int dx = 0; dx < kSupersampling; ++dx) {
              sum += pixels[4 * ((static_cast<std::size_t>(y) * kSupersampling + dy) * w +
                                 x * kSupersampling + dx) +
                            c];
            }
          }
          // GL's rows run from the bottom; the image's from the top.
          image.rgb[3 * (static_cast<std::size_t>(height - 1 - y) * width + x) + c] =
              static_cast<unsigned char>((sum + kSupersampling * kSupersampling / 2) /
                                         (kSupersampling * kSupersampling));
        }
      }
    }
    images.push_back(std::move(image));
  }
  gl.DeleteProgram(program);
  gl.DeleteRenderbuffers(2, buffers);
  gl.DeleteFramebuffers(1, &framebuffer);
  gl.DeleteBuffers(1, &buffer);
  gl.DeleteVertexArrays(1, &vao);
  return images;
}

}  // namespace roving
