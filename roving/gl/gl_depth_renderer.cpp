// The Z-buffer renderer on OpenGL 4.5 core: depth-only FBO with 32-bit float depth, whole-model
// orthographic views, and batches of one-pixel tiles (one per surface-roving camera).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gl_api.h"
#include "gl_context.h"
#include "gl_program.h"
#include "roving/core/error.h"
#include "roving/gl/depth_renderer.h"

namespace roving {
namespace {

// Whole-model view: the camera's normalised frame is computed per vertex (positions are
// relative to the model's box centre, so float keeps ~1e-7 of the model size).
constexpr const char* kViewVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform vec3 centre;          // camera centre, same frame as position
uniform vec3 right_scaled;    // right / half_width
uniform vec3 up_scaled;       // up / half_height
uniform vec3 forward_scaled;  // forward / (2 half_depth)
void main() {
  vec3 p = position - centre;
  float z = dot(p, forward_scaled) + 0.5;  // 0 at the near face, 1 at the far face
  gl_Position = vec4(dot(p, right_scaled), dot(p, up_scaled), 2.0 * z - 1.0, 1.0);
}
)";

// Roving tiles: vertices arrive in their sample camera's normalised frame; tile k is one pixel
// whose centre is that camera's central ray; clip distances keep each triangle inside its tile.
constexpr const char* kTileVertexShader = R"(#version 450 core
layout(location = 0) in vec3 normalised;
layout(location = 1) in uint tile;
uniform ivec2 grid;  // columns, rows
out float gl_ClipDistance[4];
void main() {
  uint columns = uint(grid.x);
  vec2 pixel = vec2(float(tile % columns), float(tile / columns)) + 0.5 + 0.5 * normalised.xy;
  gl_Position = vec4(2.0 * pixel / vec2(grid) - 1.0, 2.0 * normalised.z - 1.0, 1.0);
  gl_ClipDistance[0] = 1.0 - normalised.x;
  gl_ClipDistance[1] = 1.0 + normalised.x;
  gl_ClipDistance[2] = 1.0 - normalised.y;
  gl_ClipDistance[3] = 1.0 + normalised.y;
}
)";

// Depth 1 (the far plane, as a clear leaves it) over rectangles given in pixels.
constexpr const char* kFarVertexShader = R"(#version 450 core
layout(location = 0) in vec2 pixel;
uniform float resolution;
void main() {
  gl_Position = vec4(2.0 * pixel / resolution - 1.0, 1.0, 1.0);
}
)";

constexpr const char* kDepthOnlyFragmentShader = R"(#version 450 core
void main() {}
)";

class GlDepthRenderer final : public DepthRenderer {
 public:
  explicit GlDepthRenderer(GlBackend backend) : context_(gl::make_context(backend)) {
    gl_.load([this](const char* name) { return context_->proc_address(name); }, context_->platform());
    info_.backend = context_->platform();
    info_.vendor = text(GL_VENDOR);
    info_.renderer = text(GL_RENDERER);
    info_.version = text(GL_VERSION);
    GLint renderbuffer = 0, viewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    max_size_ = std::min({renderbuffer, viewport[0], viewport[1]});
    view_program_ = link(kViewVertexShader, "view");
    tile_program_ = link(kTileVertexShader, "tile");
    far_program_ = link(kFarVertexShader, "far");
    gl_.GenVertexArrays(1, &model_vao_);
    gl_.GenVertexArrays(1, &tile_vao_);
    gl_.GenVertexArrays(1, &far_vao_);
    gl_.GenBuffers(1, &model_vertices_);
    gl_.GenBuffers(1, &model_indices_);
    gl_.GenBuffers(1, &tile_vertices_);
    gl_.GenBuffers(1, &part_buffer_);
    gl_.GenBuffers(1, &far_vertices_);
    gl_.BindVertexArray(far_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, far_vertices_);
    gl_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    gl_.EnableVertexAttribArray(0);
    gl_.BindVertexArray(tile_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, tile_vertices_);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(TileVertex), nullptr);
    gl_.VertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(TileVertex),
                             reinterpret_cast<void*>(offsetof(TileVertex, tile)));
    gl_.EnableVertexAttribArray(0);
    gl_.EnableVertexAttribArray(1);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    check("initialisation");
  }

  ~GlDepthRenderer() override {
    try {
      context_->make_current();
    } catch (const Error&) {
      return;  // nothing can be freed without the context; destroying it frees all
    }
    gl_.DeleteBuffers(1, &model_vertices_);
    gl_.DeleteBuffers(1, &model_indices_);
    gl_.DeleteBuffers(1, &tile_vertices_);
    gl_.DeleteBuffers(1, &part_buffer_);
    gl_.DeleteBuffers(1, &far_vertices_);
    gl_.DeleteVertexArrays(1, &model_vao_);
    gl_.DeleteVertexArrays(1, &tile_vao_);
    gl_.DeleteVertexArrays(1, &far_vao_);
    gl_.DeleteProgram(view_program_);
    gl_.DeleteProgram(tile_program_);
    gl_.DeleteProgram(far_program_);
    if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
    if (depth_buffer_) gl_.DeleteRenderbuffers(1, &depth_buffer_);
  }

  RendererInfo info() const override { return info_; }
  int max_framebuffer_size() const override { return max_size_; }

  void upload_model(const TriangleMesh& mesh) override {
    context_->make_current();
    model_origin_ = mesh.bounding_box().centre();
    std::vector<float> positions;
    positions.reserve(3 * mesh.vertex_count());
    for (const Vec3& p : mesh.positions()) {
      const Vec3 q = p - model_origin_;
      positions.insert(positions.end(), {float(q.x()), float(q.y()), float(q.z())});
    }
    std::vector<unsigned> indices;
    indices.reserve(3 * mesh.triangle_count());
    for (const Triangle& t : mesh.triangles())
      indices.insert(indices.end(), {unsigned(t[0]), unsigned(t[1]), unsigned(t[2])});
    gl_.BindVertexArray(model_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, model_vertices_);
    gl_.BufferData(GL_ARRAY_BUFFER, positions.size() * sizeof(float), positions.data(), GL_STATIC_DRAW);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl_.EnableVertexAttribArray(0);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, model_indices_);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, indices.size() * sizeof(unsigned), indices.data(),
                   GL_STATIC_DRAW);
    model_index_count_ = static_cast<GLsizei>(indices.size());
    model_vertex_count_ = mesh.vertex_count();
    check("uploading the test model");
  }

  void render_view(const OrthoCamera& camera, int resolution, std::vector<float>& depth) override {
    context_->make_current();
    require_view(resolution);
    bind_framebuffer(resolution, resolution);
    use_view_program(camera);
    gl_.BindVertexArray(model_vao_);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, model_indices_);
    gl_.DrawElements(GL_TRIANGLES, model_index_count_, GL_UNSIGNED_INT, nullptr);
    read_depth(resolution, resolution, depth);
    check("rendering a view");
  }

  void render_view_part(const OrthoCamera& camera, int resolution, const PixelRect& rect,
                        const std::vector<PixelRect>& wanted, const std::vector<std::uint32_t>& corners,
                        std::vector<float>& depth) override {
    context_->make_current();
    require_view(resolution);
    const auto inside = [&](const PixelRect& r, const PixelRect& outer) {
      return r.x0 >= outer.x0 && r.y0 >= outer.y0 && r.x1 <= outer.x1 && r.y1 <= outer.y1;
    };
    if (!inside(rect, {0, 0, resolution, resolution})) {
      throw Error(fmt::format("gl: pixel rectangle [{}, {}) x [{}, {}) outside a {}-pixel view", rect.x0,
                              rect.x1, rect.y0, rect.y1, resolution));
    }
    if (!std::all_of(wanted.begin(), wanted.end(), [&](const PixelRect& r) { return inside(r, rect); }))
      throw Error("gl: a wanted part of a view lies outside its pixel rectangle");
    const bool corners_valid =
        corners.size() % 3 == 0 &&
        std::all_of(corners.begin(), corners.end(), [&](std::uint32_t v) { return v < model_vertex_count_; });
    if (!corners_valid) {
      throw Error(fmt::format("gl: part of a view needs three corners a triangle, each below {} vertices",
                              model_vertex_count_));
    }
    depth.resize(static_cast<std::size_t>(resolution) * resolution);
    if (rect.empty()) return;
    // Only the rectangle is drawn and read (the scissor box bounds both), and only the wanted
    // pixels in it are cleared: a scissored clear costs as much as drawing the whole rectangle.
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
    bind_framebuffer(resolution, resolution, /*clear=*/false);
    draw_far(resolution, wanted);
    if (!corners.empty()) {
      use_view_program(camera);
      gl_.BindVertexArray(model_vao_);
      gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, part_buffer_);
      gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, corners.size() * sizeof(std::uint32_t), corners.data(),
                     GL_STREAM_DRAW);
      gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(corners.size()), GL_UNSIGNED_INT, nullptr);
      gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, model_indices_);
    }
    // Read the rectangle straight into its place in the full-size image.
    gl_.PixelStorei(GL_PACK_ROW_LENGTH, resolution);
    gl_.ReadPixels(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0, GL_DEPTH_COMPONENT, GL_FLOAT,
                   depth.data() + static_cast<std::size_t>(rect.y0) * resolution + rect.x0);
    gl_.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl_.Disable(GL_SCISSOR_TEST);
    check("rendering part of a view");
  }

  void render_tiles(const std::vector<TileVertex>& vertices, std::size_t tile_count,
                    std::vector<float>& depth) override {
    context_->make_current();
    const std::size_t max_tiles = static_cast<std::size_t>(max_size_) * max_size_;
    if (tile_count == 0 || tile_count > max_tiles) {
      throw Error(fmt::format("gl: a tile batch must hold 1..{} tiles, found {}", max_tiles, tile_count));
    }
    const int columns = std::min<int>(max_size_, static_cast<int>(std::ceil(std::sqrt(double(tile_count)))));
    const int rows = static_cast<int>((tile_count + columns - 1) / columns);
    bind_framebuffer(columns, rows);
    if (!vertices.empty()) {
      gl_.UseProgram(tile_program_);
      gl_.Uniform2i(gl_.GetUniformLocation(tile_program_, "grid"), columns, rows);
      for (int plane = 0; plane < 4; ++plane) gl_.Enable(GL_CLIP_DISTANCE0 + plane);
      gl_.BindVertexArray(tile_vao_);
      gl_.BindBuffer(GL_ARRAY_BUFFER, tile_vertices_);
      gl_.BufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(TileVertex), vertices.data(), GL_STREAM_DRAW);
      gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
      for (int plane = 0; plane < 4; ++plane) gl_.Disable(GL_CLIP_DISTANCE0 + plane);
    }
    read_depth(columns, rows, depth);
    depth.resize(tile_count);
    check("rendering a tile batch");
  }

 private:
  void require_view(int resolution) const {
    if (model_index_count_ == 0) throw Error("gl: render_view() before upload_model()");
    if (resolution < 1 || resolution > max_size_) {
      throw Error(fmt::format("--resolution: expected 1..{} (this context's largest framebuffer), found {}",
                              max_size_, resolution));
    }
  }

  void use_view_program(const OrthoCamera& camera) {
    gl_.UseProgram(view_program_);
    const Vec3 centre = camera.centre - model_origin_;
    const Vec3 right = camera.right / camera.half_width, up = camera.up / camera.half_height;
    const Vec3 forward = camera.forward / (2 * camera.half_depth);
    uniform3(view_program_, "centre", centre);
    uniform3(view_program_, "right_scaled", right);
    uniform3(view_program_, "up_scaled", up);
    uniform3(view_program_, "forward_scaled", forward);
  }

  std::string text(GLenum name) const {
    const auto* s = reinterpret_cast<const char*>(gl_.GetString(name));
    return s ? s : "";
  }

  void check(const char* what) const { gl::check_error(gl_, info_.backend, what); }

  GLuint link(const char* vertex_source, const char* name) const {
    return gl::link_program(gl_, info_.backend, name, vertex_source, kDepthOnlyFragmentShader);
  }

  void uniform3(GLuint program, const char* name, const Vec3& v) const {
    gl_.Uniform3f(gl_.GetUniformLocation(program, name), float(v.x()), float(v.y()), float(v.z()));
  }

  // Depth 1 over the rectangles, one draw for all: what a clear gives, only there.
  void draw_far(int resolution, const std::vector<PixelRect>& rects) {
    if (rects.empty()) return;
    std::vector<float> corners;
    corners.reserve(12 * rects.size());
    for (const PixelRect& r : rects) {
      const float x0 = float(r.x0), y0 = float(r.y0), x1 = float(r.x1), y1 = float(r.y1);
      corners.insert(corners.end(), {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1});
    }
    gl_.UseProgram(far_program_);
    gl_.Uniform1f(gl_.GetUniformLocation(far_program_, "resolution"), float(resolution));
    gl_.BindVertexArray(far_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, far_vertices_);
    gl_.BufferData(GL_ARRAY_BUFFER, corners.size() * sizeof(float), corners.data(), GL_STREAM_DRAW);
    gl_.DepthFunc(GL_ALWAYS);
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(corners.size() / 2));
    gl_.DepthFunc(GL_LESS);
  }

  // A depth-only framebuffer of at least width x height (grown, never shrunk), with the viewport
  // on its used corner, cleared to 1 there unless `clear` is false.
  void bind_framebuffer(int width, int height, bool clear = true) {
    if (width > fb_width_ || height > fb_height_) {
      fb_width_ = std::max(fb_width_, width);
      fb_height_ = std::max(fb_height_, height);
      if (!framebuffer_) gl_.GenFramebuffers(1, &framebuffer_);
      if (!depth_buffer_) gl_.GenRenderbuffers(1, &depth_buffer_);
      gl_.BindRenderbuffer(GL_RENDERBUFFER, depth_buffer_);
      // 32-bit float depth: OSMesa's default framebuffer stays at 24 bits whatever is asked.
      gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, fb_width_, fb_height_);
      gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
      gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer_);
      gl_.DrawBuffer(GL_NONE);
      gl_.ReadBuffer(GL_NONE);
      const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
      if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error(fmt::format("gl ({}): a {} x {} float-depth framebuffer is incomplete (status 0x{:x})",
                                info_.backend, fb_width_, fb_height_, status));
      }
      check("creating the framebuffer");
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    gl_.Viewport(0, 0, width, height);
    if (!clear) return;
    gl_.ClearDepth(1.0);
    gl_.Clear(GL_DEPTH_BUFFER_BIT);
  }

  void read_depth(int width, int height, std::vector<float>& depth) const {
    depth.resize(static_cast<std::size_t>(width) * height);
    gl_.ReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  }

  std::unique_ptr<gl::Context> context_;
  gl::Api gl_;
  RendererInfo info_;
  int max_size_ = 0;
  GLuint view_program_ = 0, tile_program_ = 0, far_program_ = 0;
  GLuint model_vao_ = 0, tile_vao_ = 0, model_vertices_ = 0, model_indices_ = 0, tile_vertices_ = 0;
  GLuint far_vao_ = 0, far_vertices_ = 0;
  GLsizei model_index_count_ = 0;
  std::size_t model_vertex_count_ = 0;
  GLuint part_buffer_ = 0;
  Vec3 model_origin_ = Vec3::Zero();
  GLuint framebuffer_ = 0, depth_buffer_ = 0;
  int fb_width_ = 0, fb_height_ = 0;
};

}  // namespace

std::unique_ptr<DepthRenderer> make_depth_renderer(GlBackend backend) {
  return std::make_unique<GlDepthRenderer>(backend);
}

}  // namespace roving
