// Orthographic cameras and backend names (GL-free half of depth_renderer.h).
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "roving/core/error.h"
#include "roving/gl/depth_renderer.h"

namespace roving {

const char* to_string(GlBackend backend) {
  return backend == GlBackend::OSMesa ? "osmesa" : "egl";
}

GlBackend parse_gl_backend(const std::string& text) {
  if (text.empty()) return default_gl_backend();
  if (text == "osmesa") return GlBackend::OSMesa;
  if (text == "egl") return GlBackend::Egl;
  throw Error(fmt::format("--backend: expected osmesa or egl, found '{}'", text));
}

GlBackend default_gl_backend() {
  const char* text = std::getenv("ROVING_GL_BACKEND");
  if (!text || !*text || std::string(text) == "osmesa") return GlBackend::OSMesa;
  if (std::string(text) == "egl") return GlBackend::Egl;
  throw Error(fmt::format("ROVING_GL_BACKEND: expected osmesa or egl, found '{}'", text));
}

OrthoCamera OrthoCamera::looking_along(const Vec3& forward, const Vec3& centre, double half_width,
                                       double half_height, double half_depth) {
  OrthoCamera camera;
  camera.forward = forward.normalized();
  const Vec3 helper = std::abs(camera.forward.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  camera.right = camera.forward.cross(helper).normalized();
  camera.up = camera.right.cross(camera.forward);  // right, up, forward: left-handed screen frame
  camera.centre = centre;
  camera.half_width = half_width;
  camera.half_height = half_height;
  camera.half_depth = half_depth;
  return camera;
}

Vec3 OrthoCamera::to_normalised(const Vec3& p) const {
  const Vec3 q = p - centre;
  return {q.dot(right) / half_width, q.dot(up) / half_height, q.dot(forward) / (2 * half_depth) + 0.5};
}

}  // namespace roving
