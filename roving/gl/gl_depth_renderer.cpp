// The Z-buffer renderer on OpenGL 4.5 core: depth-only FBO with 32-bit float depth, whole-model
// orthographic views, and batches of one-pixel tiles (one per surface-roving camera).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "compute_roving.h"
#include "view_lines.h"
#include "depth_renderer_shaders.h"
#include "gl_api.h"
#include "gl_context.h"
#include "gl_program.h"
#include "roving/core/error.h"
#include "roving/gl/depth_renderer.h"

namespace roving {
namespace {

using namespace depth_shaders;

// Where a draw's fragments go: depth always; with colour, attachment 0 (RGBA32F).
enum class Outputs { Depth, Colour };

class GlDepthRenderer final : public DepthRenderer {
 public:
  GlDepthRenderer(GlBackend backend, bool gl_works_alone) : context_(gl::make_context(backend, gl_works_alone)) {
    gl_.load([this](const char* name) { return context_->proc_address(name); }, context_->platform());
    info_.backend = context_->platform();
    info_.vendor = text(GL_VENDOR);
    info_.renderer = text(GL_RENDERER);
    info_.version = text(GL_VERSION);
    GLint renderbuffer = 0, viewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    max_size_ = std::min({renderbuffer, viewport[0], viewport[1]});
    GLint max_block = 0;
    gl_.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    max_storage_block_ = max_block;
    view_program_ = link(kViewVertexShader, "view");
    const std::string tile_source = std::string("#version 450 core\n") + kTileVertexShader;
    const std::string shaded_tile_source =
        std::string("#version 450 core\n#define SHADED\n") + kTileVertexShader;
    tile_program_ = link(tile_source.c_str(), "tile");
    tile_shade_program_ =
        gl::link_program(gl_, info_.backend, "shaded tile", shaded_tile_source.c_str(), kShadeFragmentShader);
    shaded_view_program_ =
        gl::link_program(gl_, info_.backend, "shaded view", kShadedViewVertexShader, kShadeFragmentShader);
    tile_face_program_ = gl::link_compute_program(gl_, info_.backend, "tile faces", kTileFaceComputeShader);
    far_program_ = gl::link_program(gl_, info_.backend, "far", kFarVertexShader, kFarFragmentShader);
    gl_.GenVertexArrays(1, &model_vao_);
    gl_.GenVertexArrays(1, &tile_vao_);
    gl_.GenVertexArrays(1, &tile_face_vao_);
    gl_.GenVertexArrays(1, &far_vao_);
    gl_.GenVertexArrays(1, &tile_shade_vao_);
    gl_.GenBuffers(1, &tile_shades_);
    gl_.GenVertexArrays(1, &shaded_model_vao_);
    gl_.GenBuffers(1, &shaded_model_);
    gl_.GenBuffers(kStorageBuffers, tile_face_buffers_);
    gl_.GenBuffers(1, &model_vertices_);
    gl_.GenBuffers(1, &model_indices_);
    gl_.GenBuffers(1, &tile_vertices_);
    gl_.GenBuffers(1, &part_buffer_);
    gl_.GenBuffers(1, &far_vertices_);
    gl_.BindVertexArray(far_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, far_vertices_);
    gl_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
    gl_.EnableVertexAttribArray(0);
    // Tile vertices from the CPU, and from the compute stage (render_tile_faces()).
    for (const auto& [vao, buffer] :
         {std::pair(tile_vao_, tile_vertices_), std::pair(tile_shade_vao_, tile_vertices_),
          std::pair(tile_face_vao_, tile_face_buffers_[kVertices])}) {
      gl_.BindVertexArray(vao);
      gl_.BindBuffer(GL_ARRAY_BUFFER, buffer);
      gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(TileVertex), nullptr);
      gl_.VertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(TileVertex),
                               reinterpret_cast<void*>(offsetof(TileVertex, tile)));
      gl_.EnableVertexAttribArray(0);
      gl_.EnableVertexAttribArray(1);
    }
    // A shaded tile's colour factor and texture coordinates, from their own buffer.
    gl_.BindVertexArray(tile_shade_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, tile_shades_);
    gl_.VertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(TileShade), nullptr);
    gl_.VertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, sizeof(TileShade),
                            reinterpret_cast<void*>(offsetof(TileShade, u)));
    gl_.EnableVertexAttribArray(2);
    gl_.EnableVertexAttribArray(3);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    check("initialisation");
  }

  ~GlDepthRenderer() override {
    try {
      context_->make_current();
    } catch (const Error&) {
      compute_roving_.release();  // their GL objects go with the context
      view_lines_.release();
      return;  // nothing can be freed without the context; destroying it frees all
    }
    compute_roving_.reset();
    view_lines_.reset();
    gl_.DeleteBuffers(1, &model_vertices_);
    gl_.DeleteBuffers(1, &model_indices_);
    gl_.DeleteBuffers(1, &tile_vertices_);
    gl_.DeleteBuffers(1, &part_buffer_);
    gl_.DeleteBuffers(1, &far_vertices_);
    gl_.DeleteVertexArrays(1, &model_vao_);
    gl_.DeleteVertexArrays(1, &tile_vao_);
    gl_.DeleteVertexArrays(1, &tile_face_vao_);
    gl_.DeleteVertexArrays(1, &far_vao_);
    gl_.DeleteVertexArrays(1, &tile_shade_vao_);
    gl_.DeleteBuffers(1, &tile_shades_);
    gl_.DeleteVertexArrays(1, &shaded_model_vao_);
    gl_.DeleteBuffers(1, &shaded_model_);
    gl_.DeleteProgram(shaded_view_program_);
    gl_.DeleteBuffers(kStorageBuffers, tile_face_buffers_);
    if (!textures_.empty()) gl_.DeleteTextures(GLsizei(textures_.size()), textures_.data());
    gl_.DeleteProgram(view_program_);
    gl_.DeleteProgram(tile_shade_program_);
    gl_.DeleteProgram(tile_program_);
    gl_.DeleteProgram(far_program_);
    gl_.DeleteProgram(tile_face_program_);
    if (framebuffer_) gl_.DeleteFramebuffers(1, &framebuffer_);
    if (depth_buffer_) gl_.DeleteRenderbuffers(1, &depth_buffer_);
    if (colour_buffer_) gl_.DeleteRenderbuffers(1, &colour_buffer_);
  }

  RendererInfo info() const override { return info_; }
  int max_framebuffer_size() const override { return max_size_; }

  void upload_model(const TriangleMesh& mesh, bool for_tile_faces) override {
    context_->make_current();
    if (for_tile_faces) {
      // A shader sees no more of a buffer than the context's largest storage block.
      const std::size_t bytes = std::max(24 * mesh.vertex_count(), 12 * mesh.triangle_count());
      if (max_storage_block_ > 0 && bytes > static_cast<std::size_t>(max_storage_block_)) {
        throw Error(fmt::format(
            "gl ({}): the test model's {} vertices and {} triangles take {} bytes in a storage buffer, more than "
            "this context's largest storage block ({} bytes); use --camera-geometry cpu",
            info_.backend, mesh.vertex_count(), mesh.triangle_count(), bytes, max_storage_block_));
      }
    }
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
    model_triangle_count_ = for_tile_faces ? mesh.triangle_count() : 0;
    if (for_tile_faces) {
      // The positions as they are, in double: the cameras' frames are computed from them as the
      // CPU computes them.
      std::vector<double> exact;
      exact.reserve(3 * mesh.vertex_count());
      for (const Vec3& p : mesh.positions()) exact.insert(exact.end(), {p.x(), p.y(), p.z()});
      upload_storage(kPositions, exact);
      upload_storage(kCorners, indices);
    }
    check("uploading the test model");
  }

  void upload_materials(const std::vector<Material>& materials) override {
    context_->make_current();
    GLint max_texture = 0;
    gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    if (!textures_.empty()) gl_.DeleteTextures(GLsizei(textures_.size()), textures_.data());
    textures_.assign(materials.size(), 0);
    gl_.GenTextures(GLsizei(textures_.size()), textures_.data());
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const auto wrap = [](Wrap w) {
      return w == Wrap::Repeat ? GL_REPEAT : w == Wrap::ClampToEdge ? GL_CLAMP_TO_EDGE : GL_MIRRORED_REPEAT;
    };
    static const std::uint8_t white[3] = {255, 255, 255};
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const Texture* texture = materials[m].texture.get();
      if (texture && std::max(texture->width, texture->height) > max_texture) {
        throw Error(fmt::format("gl ({}): texture {} is {} x {}; this context takes at most {} a side",
                                info_.backend, texture->source, texture->width, texture->height,
                                max_texture));
      }
      const Sampler& sampler = materials[m].sampler;
      const GLint filter = sampler.filter == Filter::Linear ? GL_LINEAR : GL_NEAREST;
      gl_.BindTexture(GL_TEXTURE_2D, textures_[m]);
      // Stored as float (the 8-bit values exactly): an 8-bit texture is filtered with 8-bit
      // results on llvmpipe, whose rounding alone cost 0.3 dB of PSNR near 48 dB. Past 2^24
      // texels (200 MB as float) as stored, 8-bit.
      const int width = texture ? texture->width : 1, height = texture ? texture->height : 1;
      const std::uint8_t* codes = texture ? texture->rgb.data() : white;
      if (static_cast<long long>(width) * height <= kMaxFloatTexels) {
        const std::vector<float> texels = as_fractions(codes, 3 * static_cast<std::size_t>(width) * height);
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, texels.data());
      } else {
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE, codes);
      }
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap(sampler.wrap_s));
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap(sampler.wrap_t));
    }
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl_.UseProgram(tile_shade_program_);
    gl_.Uniform1i(gl_.GetUniformLocation(tile_shade_program_, "surface"), 0);
    gl_.ActiveTexture(GL_TEXTURE0);
    check("uploading the textures");
  }

  void upload_shaded_model(const TriangleMesh& mesh, const std::vector<TileShade>& corner_shades,
                           const std::vector<std::uint32_t>& face_materials) override {
    context_->make_current();
    if (corner_shades.size() != 3 * mesh.triangle_count() ||
        (!face_materials.empty() && face_materials.size() != mesh.triangle_count())) {
      throw Error(fmt::format(
          "gl: a shaded model of {} triangles needs a shade per corner and a material per triangle",
          mesh.triangle_count()));
    }
    // Corner by corner, material by material: position (relative to the box's centre, as
    // upload_model()), then the shade.
    shaded_origin_ = mesh.bounding_box().centre();
    std::uint32_t materials = 1;
    for (const std::uint32_t m : face_materials) materials = std::max(materials, m + 1);
    std::vector<float> corners;
    corners.reserve(8 * corner_shades.size());
    shaded_runs_.clear();
    for (std::uint32_t m = 0; m < materials; ++m) {
      const std::size_t before = corners.size();
      for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
        if ((face_materials.empty() ? 0 : face_materials[f]) != m) continue;
        for (int c = 0; c < 3; ++c) {
          const Vec3 q = mesh.positions()[mesh.triangles()[f][c]] - shaded_origin_;
          const TileShade& s = corner_shades[3 * f + c];
          corners.insert(corners.end(), {float(q.x()), float(q.y()), float(q.z()), s.r, s.g, s.b, s.u, s.v});
        }
      }
      if (corners.size() > before) shaded_runs_.push_back({m, (corners.size() - before) / 8});
    }
    gl_.BindVertexArray(shaded_model_vao_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, shaded_model_);
    gl_.BufferData(GL_ARRAY_BUFFER, corners.size() * sizeof(float), corners.data(), GL_STATIC_DRAW);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), nullptr);
    gl_.VertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float),
                            reinterpret_cast<void*>(3 * sizeof(float)));
    gl_.VertexAttribPointer(3, 2, GL_FLOAT, GL_FALSE, 8 * sizeof(float),
                            reinterpret_cast<void*>(6 * sizeof(float)));
    for (const GLuint attribute : {0u, 2u, 3u}) gl_.EnableVertexAttribArray(attribute);
    check("uploading the shaded model");
  }

  void render_shaded_view(const OrthoCamera& camera, int resolution, bool cull_back_faces,
                          std::vector<float>& depth, std::vector<Colour>& colour) override {
    context_->make_current();
    if (resolution < 1 || resolution > max_size_) {
      throw Error(
          fmt::format("gl: a shaded view of {} pixels; this context takes 1..{}", resolution, max_size_));
    }
    for (const MaterialRun& run : shaded_runs_) {
      if (run.material >= textures_.size()) throw Error("gl: render_shaded_view() before upload_materials()");
    }
    bind_framebuffer(resolution, resolution, Outputs::Colour);
    use_view_program(camera, shaded_view_program_, shaded_origin_);
    if (cull_back_faces) gl_.Enable(GL_CULL_FACE);
    gl_.BindVertexArray(shaded_model_vao_);
    std::size_t first = 0;
    for (const MaterialRun& run : shaded_runs_) {
      gl_.BindTexture(GL_TEXTURE_2D, textures_[run.material]);
      gl_.DrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(run.vertex_count));
      first += run.vertex_count;
    }
    gl_.Disable(GL_CULL_FACE);
    read_depth(resolution, resolution, depth);
    read_colour(resolution, resolution, depth, colour);
    check("rendering a shaded view");
  }

  void render_view(const OrthoCamera& camera, int resolution, std::vector<float>& depth) override {
    context_->make_current();
    require_view(resolution);
    bind_framebuffer(resolution, resolution);
    use_view_program(camera, view_program_, model_origin_);
    gl_.BindVertexArray(model_vao_);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, model_indices_);
    gl_.DrawElements(GL_TRIANGLES, model_index_count_, GL_UNSIGNED_INT, nullptr);
    read_depth(resolution, resolution, depth);
    check("rendering a view");
  }

  void render_view_part(const OrthoCamera& camera, int resolution, const PixelRect& rect,
                        const std::vector<PixelRect>& wanted, const std::vector<std::uint32_t>& corners,
                        std::vector<float>* depth) override {
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
    if (depth) depth->resize(static_cast<std::size_t>(resolution) * resolution);
    if (rect.empty()) return;
    // Only the rectangle is drawn and read (the scissor box bounds both), and only the wanted
    // pixels in it are cleared: a scissored clear costs as much as drawing the whole rectangle.
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0);
    bind_framebuffer(resolution, resolution, Outputs::Depth, /*clear=*/false);
    draw_far(resolution, wanted);
    if (!corners.empty()) {
      use_view_program(camera, view_program_, model_origin_);
      gl_.BindVertexArray(model_vao_);
      gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, part_buffer_);
      gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, corners.size() * sizeof(std::uint32_t), corners.data(),
                     GL_STREAM_DRAW);
      gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(corners.size()), GL_UNSIGNED_INT, nullptr);
      gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, model_indices_);
    }
    // Read the rectangle straight into its place in the full-size image.
    if (depth) {
      gl_.PixelStorei(GL_PACK_ROW_LENGTH, resolution);
      gl_.ReadPixels(rect.x0, rect.y0, rect.x1 - rect.x0, rect.y1 - rect.y0, GL_DEPTH_COMPONENT, GL_FLOAT,
                     depth->data() + static_cast<std::size_t>(rect.y0) * resolution + rect.x0);
      gl_.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    }
    gl_.Disable(GL_SCISSOR_TEST);
    check("rendering part of a view");
  }

  void render_tiles(const std::vector<TileVertex>& vertices, std::size_t tile_count,
                    std::vector<float>& depth) override {
    context_->make_current();
    const auto [columns, rows] = tile_grid(tile_count);
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

  void render_coloured_tiles(const std::vector<TileVertex>& vertices, const std::vector<TileShade>& shades,
                             const std::vector<MaterialRun>& runs, std::size_t tile_count,
                             std::vector<float>& depth, std::vector<Colour>& colour) override {
    context_->make_current();
    std::size_t run_vertices = 0;
    for (const MaterialRun& run : runs) {
      if (run.material >= textures_.size()) {
        throw Error(
            fmt::format("gl: a tile run names material {} of {} uploaded", run.material, textures_.size()));
      }
      run_vertices += run.vertex_count;
    }
    if (shades.size() != vertices.size() || run_vertices != vertices.size()) {
      throw Error(fmt::format("gl: {} tile vertices need as many shades and run vertices, found {} and {}",
                              vertices.size(), shades.size(), run_vertices));
    }
    const auto [columns, rows] = tile_grid(tile_count);
    bind_framebuffer(columns, rows, Outputs::Colour);
    if (!vertices.empty()) {
      gl_.UseProgram(tile_shade_program_);
      gl_.Uniform2i(gl_.GetUniformLocation(tile_shade_program_, "grid"), columns, rows);
      for (int plane = 0; plane < 4; ++plane) gl_.Enable(GL_CLIP_DISTANCE0 + plane);
      gl_.BindVertexArray(tile_shade_vao_);
      gl_.BindBuffer(GL_ARRAY_BUFFER, tile_vertices_);
      gl_.BufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(TileVertex), vertices.data(), GL_STREAM_DRAW);
      gl_.BindBuffer(GL_ARRAY_BUFFER, tile_shades_);
      gl_.BufferData(GL_ARRAY_BUFFER, shades.size() * sizeof(TileShade), shades.data(), GL_STREAM_DRAW);
      std::size_t first = 0;
      for (const MaterialRun& run : runs) {
        gl_.BindTexture(GL_TEXTURE_2D, textures_[run.material]);
        gl_.DrawArrays(GL_TRIANGLES, static_cast<GLint>(first), static_cast<GLsizei>(run.vertex_count));
        first += run.vertex_count;
      }
      for (int plane = 0; plane < 4; ++plane) gl_.Disable(GL_CLIP_DISTANCE0 + plane);
    }
    read_depth(columns, rows, depth);
    read_colour(columns, rows, depth, colour);
    depth.resize(tile_count);
    colour.resize(tile_count);
    check("rendering a coloured tile batch");
  }

  void render_tile_faces(const std::vector<OrthoCamera>& cameras, const std::vector<TileFace>& faces,
                         std::vector<float>& depth) override {
    context_->make_current();
    if (model_triangle_count_ == 0) throw Error("gl: render_tile_faces() before upload_model(mesh, true)");
    const auto [columns, rows] = tile_grid(cameras.size());
    const bool faces_valid = std::all_of(faces.begin(), faces.end(), [&](const TileFace& f) {
      return f.tile < cameras.size() && f.face < model_triangle_count_;
    });
    if (!faces_valid) {
      throw Error(fmt::format("gl: a tile face must name one of {} tiles and one of {} triangles",
                              cameras.size(), model_triangle_count_));
    }
    bind_framebuffer(columns, rows);
    if (!faces.empty()) {
      // std430 layout of the shader's Camera: four dvec4, the extents in their w.
      std::vector<double> frames;
      frames.reserve(16 * cameras.size());
      for (const OrthoCamera& c : cameras) {
        frames.insert(frames.end(), {c.centre.x(), c.centre.y(), c.centre.z(), c.half_width,  //
                                     c.right.x(), c.right.y(), c.right.z(), c.half_height,    //
                                     c.up.x(), c.up.y(), c.up.z(), 2 * c.half_depth,          //
                                     c.forward.x(), c.forward.y(), c.forward.z(), 0.0});
      }
      upload_storage(kCameras, frames);
      upload_storage(kTileFaces, faces);
      gl_.UseProgram(tile_face_program_);
      double ring[2 * kOctagonSides];
      for (int i = 0; i < kOctagonSides; ++i) {
        const double angle = 2 * M_PI * i / kOctagonSides;  // as surface_roving.cpp's widen_edge()
        ring[2 * i] = std::cos(angle), ring[2 * i + 1] = std::sin(angle);
      }
      gl_.Uniform2dv(gl_.GetUniformLocation(tile_face_program_, "ring"), kOctagonSides, ring);
      // The compute stage's output: at most kMaxVerticesPerFace a face, kFacesPerDispatch faces
      // a pass, in a buffer made once (a fresh one each batch costs its pages again).
      if (!face_vertices_ready_) {
        gl_.BindBuffer(GL_ARRAY_BUFFER, tile_face_buffers_[kVertices]);
        gl_.BufferData(GL_ARRAY_BUFFER, kFacesPerDispatch * kMaxVerticesPerFace * sizeof(TileVertex), nullptr,
                       GL_DYNAMIC_COPY);
        gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, tile_face_buffers_[kCommand]);
        gl_.BufferData(GL_DRAW_INDIRECT_BUFFER, 4 * sizeof(GLuint), nullptr, GL_DYNAMIC_COPY);
        face_vertices_ready_ = true;
      }
      gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, kVertices, tile_face_buffers_[kVertices]);
      gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommand, tile_face_buffers_[kCommand]);
      gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, tile_face_buffers_[kCommand]);
      for (int plane = 0; plane < 4; ++plane) gl_.Enable(GL_CLIP_DISTANCE0 + plane);
      for (std::size_t first = 0; first < faces.size(); first += kFacesPerDispatch) {
        const std::size_t count = std::min(kFacesPerDispatch, faces.size() - first);
        const GLuint command[4] = {0, 1, 0, 0};  // vertex count (appended to), instances, first, base
        gl_.BufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, sizeof command, command);
        gl_.UseProgram(tile_face_program_);
        gl_.Uniform1ui(gl_.GetUniformLocation(tile_face_program_, "first_face"), GLuint(first));
        gl_.Uniform1ui(gl_.GetUniformLocation(tile_face_program_, "face_count"), GLuint(count));
        gl_.DispatchCompute(GLuint((count + 63) / 64), 1, 1);
        gl_.MemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        gl_.UseProgram(tile_program_);
        gl_.Uniform2i(gl_.GetUniformLocation(tile_program_, "grid"), columns, rows);
        gl_.BindVertexArray(tile_face_vao_);
        gl_.DrawArraysIndirect(GL_TRIANGLES, nullptr);
      }
      for (int plane = 0; plane < 4; ++plane) gl_.Disable(GL_CLIP_DISTANCE0 + plane);
    }
    read_depth(columns, rows, depth);
    depth.resize(cameras.size());
    check("rendering a tile batch built on the GPU");
  }

  void upload_grid(const GridBuckets& grid) override {
    context_->make_current();
    if (!compute_roving_) compute_roving_ = std::make_unique<gl::ComputeRoving>(gl_, info_.backend);
    compute_roving_->upload_grid(grid);
  }

  void read_view_lines(const ViewLineSetup& setup, const std::vector<double>& samples,
                       std::vector<ViewLineAnswer>& answers) override {
    context_->make_current();
    if (!framebuffer_ || setup.resolution > fb_width_ || setup.resolution > fb_height_)
      throw Error("gl: read_view_lines() before a view was drawn");
    if (!view_lines_) view_lines_ = std::make_unique<gl::ViewLines>(gl_, info_.backend);
    view_lines_->run(setup, samples, answers);
  }

  void rove_samples(const std::vector<double>& samples, const RovingSetup& setup,
                    std::vector<ComputedTile>& answers) override {
    context_->make_current();
    if (model_triangle_count_ == 0) throw Error("gl: rove_samples() before upload_model(mesh, true)");
    if (!compute_roving_) throw Error("gl: rove_samples() before upload_grid()");
    compute_roving_->run(tile_face_buffers_[kPositions], tile_face_buffers_[kCorners], samples, setup, answers);
  }

 private:
  static constexpr long long kMaxFloatTexels = 1LL << 24;
  static std::vector<float> as_fractions(const std::uint8_t* codes, std::size_t count) {
    std::vector<float> fractions(count);
    for (std::size_t i = 0; i < count; ++i) fractions[i] = codes[i] / 255.0f;
    return fractions;
  }

  // The storage buffers of render_tile_faces(), at the compute shader's bindings.
  enum StorageBuffer { kPositions, kCorners, kCameras, kTileFaces, kVertices, kCommand, kStorageBuffers };
  static constexpr int kOctagonSides = 8;
  // A face's triangle, and per edge an octagon (kOctagonSides - 2 triangles) and a strip (two).
  static constexpr std::size_t kMaxVerticesPerFace = 3 + 3 * (3 * (kOctagonSides - 2) + 6);
  static constexpr std::size_t kFacesPerDispatch = 1 << 14;

  template <class T>
  void upload_storage(StorageBuffer binding, const std::vector<T>& data) {
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, tile_face_buffers_[binding]);
    gl_.BufferData(GL_SHADER_STORAGE_BUFFER, data.size() * sizeof(T), data.data(),
                   binding == kPositions || binding == kCorners ? GL_STATIC_DRAW : GL_STREAM_DRAW);
    gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, tile_face_buffers_[binding]);
  }

  // The columns and rows of a batch of one-pixel tiles: about square, within the framebuffer.
  std::pair<int, int> tile_grid(std::size_t tile_count) const {
    const std::size_t max_tiles = static_cast<std::size_t>(max_size_) * max_size_;
    if (tile_count == 0 || tile_count > max_tiles) {
      throw Error(fmt::format("gl: a tile batch must hold 1..{} tiles, found {}", max_tiles, tile_count));
    }
    const int columns = std::min<int>(max_size_, static_cast<int>(std::ceil(std::sqrt(double(tile_count)))));
    return {columns, static_cast<int>((tile_count + columns - 1) / columns)};
  }

  void require_view(int resolution) const {
    if (model_index_count_ == 0) throw Error("gl: render_view() before upload_model()");
    if (resolution < 1 || resolution > max_size_) {
      throw Error(fmt::format("--resolution: expected 1..{} (this context's largest framebuffer), found {}",
                              max_size_, resolution));
    }
  }

  // `origin`: what the program's positions are relative to.
  void use_view_program(const OrthoCamera& camera, GLuint program, const Vec3& origin) {
    gl_.UseProgram(program);
    const Vec3 centre = camera.centre - origin;
    const Vec3 right = camera.right / camera.half_width, up = camera.up / camera.half_height;
    const Vec3 forward = camera.forward / (2 * camera.half_depth);
    uniform3(program, "centre", centre);
    uniform3(program, "right_scaled", right);
    uniform3(program, "up_scaled", up);
    uniform3(program, "forward_scaled", forward);
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

  // A framebuffer of at least width x height (grown, never shrunk): float depth, and once a
  // draw asks for it a colour attachment, the draw buffer set to `outputs`,
  // the viewport on its used corner, cleared there unless `clear` is false.
  void bind_framebuffer(int width, int height, Outputs outputs = Outputs::Depth, bool clear = true) {
    const bool more_attachments = outputs != Outputs::Depth && !colour_buffer_;
    if (width > fb_width_ || height > fb_height_ || more_attachments) {
      fb_width_ = std::max(fb_width_, width);
      fb_height_ = std::max(fb_height_, height);
      if (!framebuffer_) gl_.GenFramebuffers(1, &framebuffer_);
      gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
      // 32-bit float depth: OSMesa's default framebuffer stays at 24 bits whatever is asked.
      attach(depth_buffer_, GL_DEPTH_COMPONENT32F, GL_DEPTH_ATTACHMENT);
      if (colour_buffer_ || more_attachments) attach(colour_buffer_, GL_RGBA32F, GL_COLOR_ATTACHMENT0);
      gl_.ReadBuffer(GL_NONE);
      drawn_outputs_.reset();  // set below
      const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
      if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error(fmt::format("gl ({}): a {} x {} float-depth framebuffer is incomplete (status 0x{:x})",
                                info_.backend, fb_width_, fb_height_, status));
      }
      check("creating the framebuffer");
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    if (outputs != drawn_outputs_) {  // only on a change: a depth-only draw pays nothing for colour
      const GLenum buffer = outputs == Outputs::Colour ? GLenum(GL_COLOR_ATTACHMENT0) : GLenum(GL_NONE);
      gl_.DrawBuffers(1, &buffer);
      drawn_outputs_ = outputs;
    }
    gl_.Viewport(0, 0, width, height);
    if (!clear) return;
    gl_.ClearDepth(1.0);
    gl_.Clear(GL_DEPTH_BUFFER_BIT);
    const float no_colour[4] = {0, 0, 0, 0};
    if (outputs == Outputs::Colour) gl_.ClearBufferfv(GL_COLOR, 0, no_colour);
  }

  // (Re)allocates `buffer` at the framebuffer's size and attaches it.
  void attach(GLuint& buffer, GLenum format, GLenum attachment) {
    if (!buffer) gl_.GenRenderbuffers(1, &buffer);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, buffer);
    gl_.RenderbufferStorage(GL_RENDERBUFFER, format, fb_width_, fb_height_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, GL_RENDERBUFFER, buffer);
  }

  // The colour attachment, in code values, NaN where `depth` (read already) says nothing was drawn.
  // Read through a buffer kept between calls: a new one for each of IBSM's 2048 x 2048 views was
  // 64 MB zeroed and faulted in each time.
  void read_colour(int width, int height, const std::vector<float>& depth,
                   std::vector<Colour>& colour) const {
    const std::size_t pixels = static_cast<std::size_t>(width) * height;
    std::vector<float>& rgba = rgba_;
    rgba.resize(4 * pixels);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
    gl_.ReadBuffer(GL_NONE);
    colour.resize(pixels);
    for (std::size_t k = 0; k < pixels; ++k) {
      colour[k] = depth[k] < 1.0f ? Colour(255 * rgba[4 * k], 255 * rgba[4 * k + 1], 255 * rgba[4 * k + 2])
                                  : Colour::Constant(std::numeric_limits<float>::quiet_NaN());
    }
  }

  void read_depth(int width, int height, std::vector<float>& depth) const {
    depth.resize(static_cast<std::size_t>(width) * height);
    gl_.ReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  }

  std::unique_ptr<gl::Context> context_;
  gl::Api gl_;
  RendererInfo info_;
  int max_size_ = 0;
  long long max_storage_block_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  GLuint view_program_ = 0, tile_program_ = 0, tile_shade_program_ = 0, far_program_ = 0;
  GLuint tile_shade_vao_ = 0, tile_shades_ = 0;
  GLuint shaded_view_program_ = 0, shaded_model_vao_ = 0, shaded_model_ = 0;
  std::vector<MaterialRun> shaded_runs_;  // the shaded model's corners, material by material
  Vec3 shaded_origin_ = Vec3::Zero();
  std::vector<GLuint> textures_;     // one per material (upload_materials())
  mutable std::vector<float> rgba_;  // read_colour()'s read-back
  GLuint model_vao_ = 0, tile_vao_ = 0, model_vertices_ = 0, model_indices_ = 0, tile_vertices_ = 0;
  GLuint far_vao_ = 0, far_vertices_ = 0;
  GLuint tile_face_program_ = 0, tile_face_vao_ = 0, tile_face_buffers_[kStorageBuffers] = {};
  bool face_vertices_ready_ = false;
  std::unique_ptr<gl::ComputeRoving> compute_roving_;  // made by upload_grid()
  std::unique_ptr<gl::ViewLines> view_lines_;          // made by the first read_view_lines()
  std::size_t model_triangle_count_ = 0;  // with positions in double, for render_tile_faces()
  GLsizei model_index_count_ = 0;
  std::size_t model_vertex_count_ = 0;
  GLuint part_buffer_ = 0;
  Vec3 model_origin_ = Vec3::Zero();
  GLuint framebuffer_ = 0, depth_buffer_ = 0, colour_buffer_ = 0;
  std::optional<Outputs> drawn_outputs_;  // what the framebuffer's draw buffers are set to
  int fb_width_ = 0, fb_height_ = 0;
};

}  // namespace

std::unique_ptr<DepthRenderer> make_depth_renderer(GlBackend backend, bool gl_works_alone) {
  return std::make_unique<GlDepthRenderer>(backend, gl_works_alone);
}

}  // namespace roving
