// GL-free interface of the Z-buffer renderer (paper Section 3): orthographic depth images of a
// test model, whole views for viewpoint sampling and one-pixel tiles for surface roving.
// The GL, OSMesa and EGL code behind it lives under roving/gl/.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "roving/core/triangle_mesh.h"

namespace roving {

enum class GlBackend { OSMesa, Egl };
const char* to_string(GlBackend backend);
// Parses "osmesa" or "egl"; throws roving::Error naming `--backend` otherwise. An empty text is
// default_gl_backend().
GlBackend parse_gl_backend(const std::string& text);
// The backend used where none is named: $ROVING_GL_BACKEND (osmesa or egl; a GPU machine sets it
// once, as MUJOCO_GL or PYOPENGL_PLATFORM are set), else osmesa. Throws roving::Error naming the
// variable on any other value.
GlBackend default_gl_backend();

// An orthographic camera: it looks along `forward` at the box centred on `centre` with half
// extents `half_width` (along `right`), `half_height` (along `up`) and `half_depth` (along
// `forward`). Depth 0 is the box's near face (centre - half_depth * forward), 1 its far face;
// orthographic depth is linear, so a depth z means a distance z * 2 * half_depth from the near face.
struct OrthoCamera {
  Vec3 centre, right, up, forward;
  double half_width = 1, half_height = 1, half_depth = 1;

  // An orthonormal camera looking along `forward` (any perpendicular `right`, `up`).
  static OrthoCamera looking_along(const Vec3& forward, const Vec3& centre, double half_width,
                                   double half_height, double half_depth);
  // The point's coordinates in the camera's normalised frame: x, y in [-1, 1] across the box,
  // z in [0, 1] from the near face.
  Vec3 to_normalised(const Vec3& p) const;
};

// One vertex of a roving batch, already in its sample camera's normalised frame (x, y in [-1, 1]
// across the view volume, z in [0, 1] along its depth), and the tile (sample) it belongs to.
struct TileVertex {
  float x, y, z;
  std::uint32_t tile;
};

// One candidate of a roving batch built on the GPU: the uploaded model's triangle `face`, drawn
// in tile `tile` through that tile's camera.
struct TileFace {
  std::uint32_t tile, face;
};

// What colours a tile vertex's fragments (colour runs only): the surface's colour factor there
// (its vertex colour times its material's factor, as fractions of 255: TriangleMesh's colour) and
// its texture coordinates (glTF's, v down from the image's top row).
struct TileShade {
  float r, g, b, u, v;
};

// Consecutive tile vertices (three a triangle) drawn with one material's texture
// (upload_materials()).
struct MaterialRun {
  std::uint32_t material;
  std::size_t vertex_count;
};

// A rectangle of pixels [x0, x1) x [y0, y1) of a view (x along `right`, y along `up`).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// TEST's triangles bucketed in a uniform grid (surface roving's TriangleGrid), for
// DepthRenderer::rove_samples(): cell (x, y, z) of dims, at origin + cell * (x, y, z), lists
// entries[offsets[c] .. offsets[c + 1]) with c = (z dims[1] + y) dims[0] + x.
struct GridBuckets {
  Vec3 origin = Vec3::Zero();
  double cell = 1;
  int dims[3] = {1, 1, 1};
  const std::vector<std::uint32_t>* offsets = nullptr;
  const std::vector<std::uint32_t>* entries = nullptr;
};

// A roving camera's answer from the compute pass: the depth of its pixel centre (1: nothing
// there), whether a candidate face thin across the camera was left to the CPU's rule, and where
// asked the face its hit lies on by the rule with the rule's d there (kFaceLeft: left to the
// CPU's hit_face()).
constexpr std::uint32_t kFaceLeft = 0xFFFFFFFF;
struct ComputedTile {
  float depth;
  std::uint32_t thin;
  std::uint32_t face;
  std::uint32_t unused;
  double distance;
};

// The compute pass's cameras (surface_roving.cpp): half-width (the rule's tolerance), half-depth
// (h and the tolerance), h; and where each hit's face is asked (face_window > 0), the window
// around the cameras' d in which hit_face() looks for crossings (roving_tolerance()).
struct RovingSetup {
  double half_width = 0, half_depth = 0, max_error = 0, face_window = 0;
};

// What viewpoint sampling's lookup of a sample's normal line in a view needs beside the view's
// depth (viewpoint_sampling.cpp's ViewLine): the view's camera and size, the pixels drawn, h, and
// the bounds it derives from the view's precision (normalised depth, but min_distance: model
// units).
struct ViewLineSetup {
  OrthoCamera camera;
  int resolution = 0;
  PixelRect rect;
  double h = 0, smooth_span = 0, depth_scale = 0, crease_limit = 0, min_distance = 0, noise = 0;
};

// Whether a view resolves a sample, and its d there.
struct ViewLineAnswer {
  double d;
  std::uint32_t accepted, unused;
};

struct RendererInfo {
  std::string backend, vendor, renderer, version;
};

class DepthRenderer {
 public:
  virtual ~DepthRenderer() = default;

  virtual RendererInfo info() const = 0;
  // Largest framebuffer side the context allows (GL_MAX_RENDERBUFFER_SIZE / viewport limit).
  virtual int max_framebuffer_size() const = 0;

  // Uploads M_C once: for whole-model views, and with `for_tile_faces` also its positions in
  // double and its triangles, for render_tile_faces().
  virtual void upload_model(const TriangleMesh& mesh, bool for_tile_faces = false) = 0;
  // Uploads the textures and samplers of M_C's materials (material i's texture, or white where it
  // has none), for render_coloured_tiles(). Throws roving::Error naming a texture larger than
  // the context allows.
  virtual void upload_materials(const std::vector<Material>& materials) = 0;
  // Uploads M_C for render_shaded_view(): its triangles with each corner's shade (three a
  // triangle, corner_shades[3 f + c]) and each triangle's material (empty: all material 0); the
  // materials themselves by upload_materials().
  virtual void upload_shaded_model(const TriangleMesh& mesh, const std::vector<TileShade>& corner_shades,
                                   const std::vector<std::uint32_t>& face_materials) = 0;
  // Draws the shaded model through `camera`, unlit: each fragment the colour the tiles give it
  // (render_coloured_tiles()), back faces culled when `cull_back_faces` (a triangle's front is
  // counter-clockwise). Returns the depth as render_view() does and each pixel's colour in code
  // values (NaN where nothing was drawn), row by row from the bottom.
  virtual void render_shaded_view(const OrthoCamera& camera, int resolution, bool cull_back_faces,
                                  std::vector<float>& depth, std::vector<Colour>& colour) = 0;
  // Draws the uploaded model through `camera` into a resolution x resolution 32-bit float depth
  // buffer and returns it row by row from the bottom (x along `right`); 1 where nothing was drawn.
  virtual void render_view(const OrthoCamera& camera, int resolution, std::vector<float>& depth) = 0;
  // The same view, drawing only the triangles whose corners (indices into the uploaded model's
  // vertices, three a triangle) `corners` lists, and only the pixels in `rect`: depth has
  // resolution^2 entries; at the pixels of the `wanted` rectangles (within `rect`) they are what
  // render_view() gives wherever no omitted triangle covers the pixel; elsewhere in `rect` they
  // are undefined, and outside it left as they were. A null `depth`: nothing is read back; the
  // view stays on the GPU for read_view_lines().
  virtual void render_view_part(const OrthoCamera& camera, int resolution, const PixelRect& rect,
                                const std::vector<PixelRect>& wanted,
                                const std::vector<std::uint32_t>& corners, std::vector<float>* depth) = 0;
  // Viewpoint sampling's lookup in a compute pass on the view last drawn (its `setup.rect`, as
  // render_view_part() drew it, or the whole view): for each sample (six doubles: position,
  // normal) whether the view resolves it, and its d (view_lines_shader.h).
  virtual void read_view_lines(const ViewLineSetup& setup, const std::vector<double>& samples,
                               std::vector<ViewLineAnswer>& answers) = 0;

  // Draws `vertices` (triangles, three consecutive vertices each) into a grid of one-pixel tiles,
  // tile k at column k % columns, row k / columns, each clipped to its own view volume, and
  // returns one depth per tile (1: nothing drawn). The pixel centre of tile k is its camera's
  // central ray, so the depth read back is that ray's first crossing of what was drawn.
  virtual void render_tiles(const std::vector<TileVertex>& vertices, std::size_t tile_count,
                            std::vector<float>& depth) = 0;
  // The same tiles coloured, the frame buffer beside the Z-buffer (the paper's Section 1): each
  // vertex's fragments by shades[i] (the factor times its material's texture sampled at the
  // interpolated coordinates by the material's sampler), the vertices drawn run by run with
  // `runs`' materials. Also returns each tile's colour in code values (Colour); NaN where nothing
  // was drawn. Needs upload_materials().
  virtual void render_coloured_tiles(const std::vector<TileVertex>& vertices,
                                     const std::vector<TileShade>& shades,
                                     const std::vector<MaterialRun>& runs, std::size_t tile_count,
                                     std::vector<float>& depth, std::vector<Colour>& colour) = 0;
  // The same tiles (one per camera), their geometry built on the GPU from `faces`: for each, the
  // uploaded model's triangle in its tile's camera frame, with its edges and corners widened as
  // surface roving's CPU builds them (roving/gl_methods/surface_roving.cpp), in double as there.
  // Needs upload_model(mesh, true).
  virtual void render_tile_faces(const std::vector<OrthoCamera>& cameras, const std::vector<TileFace>& faces,
                                 std::vector<float>& depth) = 0;

  // Uploads the grid that rove_samples() walks, once (not held after).
  virtual void upload_grid(const GridBuckets& grid) = 0;
  // Exact roving's cameras with nothing drawn: for each sample (six doubles: position, normal),
  // the camera surface_roving.cpp makes for it, and in a compute pass over the grid's candidates
  // the depth at its pixel centre of what the raster path draws for them, in double; where
  // asked, the hit's face (compute_roving_shader.h). Needs upload_model(mesh, true) and
  // upload_grid().
  virtual void rove_samples(const std::vector<double>& samples, const RovingSetup& setup,
                            std::vector<ComputedTile>& answers) = 0;
};

// Creates an offscreen context and its renderer. OSMesa gives Mesa's llvmpipe; EGL tries the
// device platform (a real GPU where a driver exists), then Mesa's surfaceless platform.
// Throws roving::Error saying what failed when no context with float depth can be made.
// `gl_works_alone`: see gl::make_context().
std::unique_ptr<DepthRenderer> make_depth_renderer(GlBackend backend, bool gl_works_alone = false);

}  // namespace roving
