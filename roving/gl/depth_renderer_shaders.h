// The depth renderer's GLSL sources (gl_depth_renderer.cpp): whole-model views, roving tiles
// (drawn from vertices the CPU gives, or built on the GPU by a compute pass), their shading, and
// the far rectangles.
#pragma once

namespace roving::depth_shaders {

// Whole-model view: the camera's normalised frame is computed per vertex (positions are
// relative to the model's box centre, so float keeps ~1e-7 of the model size).
inline constexpr const char* kViewVertexShader = R"(#version 450 core
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
// Compiled twice: for depth alone, and SHADED, passing each vertex's colour factor and texture
// coordinates on to kShadeFragmentShader.
inline constexpr const char* kTileVertexShader = R"(
layout(location = 0) in vec3 normalised;
layout(location = 1) in uint tile;
#ifdef SHADED
layout(location = 2) in vec3 factor_in;
layout(location = 3) in vec2 uv_in;
out vec3 factor;
out vec2 uv;
#endif
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
#ifdef SHADED
  factor = factor_in;
  uv = uv_in;
#endif
}
)";

// A whole-model view shaded as the tiles are (render_shaded_view()): kViewVertexShader's frame,
// each corner's shade passed on to kShadeFragmentShader.
inline constexpr const char* kShadedViewVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 2) in vec3 factor_in;
layout(location = 3) in vec2 uv_in;
uniform vec3 centre;
uniform vec3 right_scaled;
uniform vec3 up_scaled;
uniform vec3 forward_scaled;
out vec3 factor;
out vec2 uv;
void main() {
  vec3 p = position - centre;
  float z = dot(p, forward_scaled) + 0.5;
  gl_Position = vec4(dot(p, right_scaled), dot(p, up_scaled), 2.0 * z - 1.0, 1.0);
  factor = factor_in;
  uv = uv_in;
}
)";

// The colour of a surface where a fragment lies: its factor (vertex colour times material
// factor) times its material's texture, sampled by the texture's own sampler state (wrap and
// filter as glTF's sampler says, no mipmaps: a sample is a point). Fractions of 255.
inline constexpr const char* kShadeFragmentShader = R"(#version 450 core
in vec3 factor;
in vec2 uv;
uniform sampler2D surface;
layout(location = 0) out vec4 colour;
void main() {
  colour = vec4(factor * texture(surface, uv).rgb, 1.0);
}
)";

// Roving tiles built on the GPU: one invocation per (tile, face) candidate appends what
// surface_roving.cpp's emit_triangles() and widen_edge() append on the CPU for it (the triangle
// in the tile camera's normalised frame; per edge, an octagon of radius 1 around its first
// corner where that is near, and a strip of half-width 1 along the part of it near the pixel),
// computed in double with the same operations in the same order (`precise`: no fused
// multiply-adds), rounded to float and appended to the tile vertices that kTileVertexShader
// draws; the draw's vertex count is kept in an indirect draw command.
inline constexpr const char* kTileFaceComputeShader = R"(#version 450 core
layout(local_size_x = 64) in;
struct Camera {
  dvec4 centre;   // w: half_width
  dvec4 right;    // w: half_height
  dvec4 up;       // w: 2 half_depth
  dvec4 forward;
};
struct TileVertex {
  float x, y, z;
  uint tile;
};
layout(std430, binding = 0) readonly buffer Positions { double positions[]; };
layout(std430, binding = 1) readonly buffer Corners { uint corners[]; };
layout(std430, binding = 2) readonly buffer Cameras { Camera cameras[]; };
layout(std430, binding = 3) readonly buffer TileFaces { uvec2 tile_faces[]; };
layout(std430, binding = 4) writeonly buffer Vertices { TileVertex vertices[]; };
layout(std430, binding = 5) buffer Command { uint vertex_count, instance_count, first_vertex, base_instance; };
uniform uint first_face, face_count;
uniform dvec2 ring[8];  // the octagon's corners around a point, as the CPU computes them

dvec3 to_normalised(Camera camera, uint vertex) {
  precise dvec3 q = dvec3(positions[3u * vertex], positions[3u * vertex + 1u], positions[3u * vertex + 2u]) -
                    camera.centre.xyz;
  precise double x = q.x * camera.right.x + q.y * camera.right.y + q.z * camera.right.z;
  precise double y = q.x * camera.up.x + q.y * camera.up.y + q.z * camera.up.z;
  precise double z = q.x * camera.forward.x + q.y * camera.forward.y + q.z * camera.forward.z;
  precise double nx = x / camera.centre.w;
  precise double ny = y / camera.right.w;
  precise double nz = z / camera.up.w + 0.5LF;
  return dvec3(nx, ny, nz);
}

uint tile;
uint next_vertex;
void emit(dvec3 p) {
  vertices[next_vertex++] = TileVertex(float(p.x), float(p.y), float(p.z), tile);
}

const double kWindow = 2.0LF;

bool octagon_needed(dvec3 p) { return abs(p.x) <= kWindow && abs(p.y) <= kWindow; }

void emit_octagon(dvec3 p) {
  dvec3 corner[8];
  for (int i = 0; i < 8; ++i) {
    precise double x = p.x + ring[i].x;
    precise double y = p.y + ring[i].y;
    corner[i] = dvec3(x, y, p.z);
  }
  for (int i = 1; i + 1 < 8; ++i) {
    emit(corner[0]);
    emit(corner[i]);
    emit(corner[i + 1]);
  }
}

// Liang-Barsky: the part of p -> q inside the window, as the strip's four corners; false where
// there is none, or it is seen end-on.
bool strip(dvec3 p, dvec3 q, out dvec3 corner[4]) {
  precise dvec3 delta = q - p;
  double enter = 0.0LF, leave = 1.0LF;
  for (int axis = 0; axis < 2; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double bound = side == 0 ? -kWindow : kWindow;
      precise double distance = bound - p[axis];
      if (delta[axis] == 0.0LF) {
        if ((bound < 0.0LF && distance > 0.0LF) || (bound > 0.0LF && distance < 0.0LF)) return false;
        continue;
      }
      precise double t = distance / delta[axis];
      if ((bound < 0.0LF) == (delta[axis] > 0.0LF)) {
        enter = max(enter, t);
      } else {
        leave = min(leave, t);
      }
    }
  }
  if (enter >= leave) return false;
  precise dvec3 start = p + enter * delta;
  precise dvec3 end = p + leave * delta;
  precise double dx = end.x - start.x;
  precise double dy = end.y - start.y;
  precise double length = sqrt(dx * dx + dy * dy);
  if (!(length > 1e-9LF)) return false;
  precise dvec3 across = dvec3((start.y - end.y) / length, (end.x - start.x) / length, 0.0LF);
  corner[0] = start + across;
  corner[1] = end + across;
  corner[2] = end - across;
  corner[3] = start - across;
  return true;
}

void main() {
  if (gl_GlobalInvocationID.x >= face_count) return;
  const uvec2 tile_face = tile_faces[first_face + gl_GlobalInvocationID.x];
  tile = tile_face.x;
  const Camera camera = cameras[tile];
  dvec3 q[3];
  for (uint c = 0u; c < 3u; ++c) q[c] = to_normalised(camera, corners[3u * tile_face.y + c]);
  for (int axis = 0; axis < 3; ++axis) {
    const double low = axis == 2 ? 0.0LF : -1.0LF;
    if ((q[0][axis] > 1.0LF && q[1][axis] > 1.0LF && q[2][axis] > 1.0LF) ||
        (q[0][axis] < low && q[1][axis] < low && q[2][axis] < low)) {
      return;
    }
  }
  bool octagon[3], has_strip[3];
  dvec3 strip_corner[3][4];
  uint count = 3u;
  for (int e = 0; e < 3; ++e) {
    octagon[e] = octagon_needed(q[e]);
    has_strip[e] = strip(q[e], q[(e + 1) % 3], strip_corner[e]);
    count += (octagon[e] ? 18u : 0u) + (has_strip[e] ? 6u : 0u);
  }
  next_vertex = atomicAdd(vertex_count, count);
  for (int c = 0; c < 3; ++c) emit(q[c]);
  for (int e = 0; e < 3; ++e) {
    if (octagon[e]) emit_octagon(q[e]);
    if (has_strip[e]) {
      for (int i = 0; i < 6; ++i) emit(strip_corner[e][int[6](0, 1, 2, 0, 2, 3)[i]]);
    }
  }
}
)";

// Depth 1 (the far plane, as a clear leaves it) over rectangles given in pixels.
inline constexpr const char* kFarVertexShader = R"(#version 450 core
layout(location = 0) in vec2 pixel;
uniform float resolution;
void main() {
  gl_Position = vec4(2.0 * pixel / resolution - 1.0, 1.0, 1.0);
}
)";

inline constexpr const char* kDepthOnlyFragmentShader = R"(#version 450 core
void main() {}
)";

// The far rectangles set depth alone.
inline constexpr const char* kFarFragmentShader = R"(#version 450 core
void main() {}
)";

}  // namespace roving::depth_shaders
