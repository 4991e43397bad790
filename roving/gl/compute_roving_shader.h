// The GLSL source of exact surface roving in a compute pass (compute_roving.cpp).
#pragma once

namespace roving::compute_shaders {

// One invocation per sample: its camera as OrthoCamera::looking_along() makes it, the walk of
// TEST's triangle grid along the camera's segment (TriangleGrid::walk), the culling of
// surface_roving.cpp's for_each_candidate(), and for each candidate the depth at the pixel centre
// of what the raster path draws for it (emit_triangles(), widen_edge()): the triangle, the
// octagons of radius 1 around its corners near the pixel, and the strips of half-width 1 along
// the part of its edges near the pixel. The nearest such depth in [0, 1) is the sample's, 1 where
// none; a face thin across the camera is left to the CPU's rule, flagged. All in double, as the
// CPU computes it (`precise`: no fused multiply-adds); coverage is closed (on a boundary counts),
// since the raster path's fill rule at a boundary is the rasteriser's choice.
inline constexpr const char* kRovingComputeShader = R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { double positions[]; };
layout(std430, binding = 1) readonly buffer Corners { uint corners[]; };
layout(std430, binding = 2) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 3) readonly buffer Entries { uint entries[]; };
layout(std430, binding = 4) readonly buffer Samples { double samples[]; };  // position, normal
struct Answer {
  float depth;  // 1: no candidate covers the pixel centre
  uint thin;    // 1: a candidate is thin across the camera (the CPU decides it)
};
layout(std430, binding = 5) writeonly buffer Answers { Answer answers[]; };
uniform uint sample_count;
uniform dvec3 grid_origin;
uniform double grid_cell;
uniform ivec3 grid_dims;
uniform double half_width, half_depth;
uniform dvec2 ring[8];  // the octagon's corners around a point, as the CPU computes them

dvec3 normalized(dvec3 v) {
  precise double squared = v.x * v.x + v.y * v.y + v.z * v.z;
  precise dvec3 unit = v / sqrt(squared);
  return unit;
}

dvec3 cross3(dvec3 a, dvec3 b) {
  precise double x = a.y * b.z - a.z * b.y;
  precise double y = a.z * b.x - a.x * b.z;
  precise double z = a.x * b.y - a.y * b.x;
  return dvec3(x, y, z);
}

double dot3(dvec3 a, dvec3 b) {
  precise double d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}

dvec3 centre, right, up, forward;

dvec3 vertex(uint v) { return dvec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]); }

const double kWindow = 2.0LF;
double best;   // nearest depth so far
bool thin_seen;

void consider(double z) {
  if (z >= 0.0LF && z < best) best = z;
}

// The octagon of radius 1 around p, if the pixel centre lies in it (closed).
void octagon(dvec3 p) {
  if (!(abs(p.x) <= kWindow && abs(p.y) <= kWindow)) return;
  for (int i = 0; i < 8; ++i) {
    precise dvec2 a = p.xy + ring[i];
    precise dvec2 b = p.xy + ring[(i + 1) % 8];
    precise double side = (b.x - a.x) * (0.0LF - a.y) - (b.y - a.y) * (0.0LF - a.x);
    if (side < 0.0LF) return;
  }
  consider(p.z);
}

// The strip of half-width 1 along the part of p -> q in the window (Liang-Barsky, as
// widen_edge()), if the pixel centre lies in it: the depth there varies along the strip alone.
void strip(dvec3 p, dvec3 q) {
  precise dvec3 delta = q - p;
  double enter = 0.0LF, leave = 1.0LF;
  for (int axis = 0; axis < 2; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double bound = side == 0 ? -kWindow : kWindow;
      precise double distance = bound - p[axis];
      if (delta[axis] == 0.0LF) {
        if ((bound < 0.0LF && distance > 0.0LF) || (bound > 0.0LF && distance < 0.0LF)) return;
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
  if (enter >= leave) return;
  precise dvec3 start = p + enter * delta;
  precise dvec3 end = p + leave * delta;
  precise double dx = end.x - start.x;
  precise double dy = end.y - start.y;
  precise double length_squared = dx * dx + dy * dy;
  precise double length = sqrt(length_squared);
  if (!(length > 1e-9LF)) return;
  precise double along = (0.0LF - start.x) * dx + (0.0LF - start.y) * dy;  // times length^2
  precise double across = dx * (0.0LF - start.y) - dy * (0.0LF - start.x);  // times length
  if (along < 0.0LF || along > length_squared || abs(across) > length) return;
  precise double z = start.z + along / length_squared * (end.z - start.z);
  consider(z);
}

// The triangle q, if the pixel centre lies in it (closed): its plane's depth there.
void triangle(dvec3 q[3]) {
  double w[3];
  for (int e = 0; e < 3; ++e) {
    const dvec3 a = q[e], b = q[(e + 1) % 3];
    precise double edge = (b.x - a.x) * (0.0LF - a.y) - (b.y - a.y) * (0.0LF - a.x);
    w[e] = edge;
  }
  const bool inside = (w[0] >= 0.0LF && w[1] >= 0.0LF && w[2] >= 0.0LF) ||
                      (w[0] <= 0.0LF && w[1] <= 0.0LF && w[2] <= 0.0LF);
  precise double sum = w[0] + w[1] + w[2];
  if (!inside || sum == 0.0LF) return;
  // w[e] is the weight of the corner opposite edge e.
  precise double z = (w[1] * q[0].z + w[2] * q[1].z + w[0] * q[2].z) / sum;
  consider(z);
}

void candidate(uint face) {
  // The corners' offsets from the camera centre along right and up, computed once for the
  // culling, the thin test and the normalised frame (OrthoCamera::to_normalised() takes the same
  // dot products of the same offsets).
  dvec3 offset[3];
  double x[3], y[3];
  for (int c = 0; c < 3; ++c) {
    offset[c] = vertex(corners[3u * face + uint(c)]) - centre;
    x[c] = dot3(offset[c], right);
    y[c] = dot3(offset[c], up);
  }
  precise double bound = half_width * (1.0LF + 1e-9LF);
  if ((x[0] > bound && x[1] > bound && x[2] > bound) || (x[0] < -bound && x[1] < -bound && x[2] < -bound) ||
      (y[0] > bound && y[1] > bound && y[2] > bound) || (y[0] < -bound && y[1] < -bound && y[2] < -bound)) {
    return;
  }
  // Thin across the camera (surface_roving.cpp's thin_across()): the CPU's rule decides it.
  double longest_squared = 0.0LF;
  for (int e = 0; e < 3; ++e) {
    const int f = (e + 1) % 3;
    precise double squared = (x[f] - x[e]) * (x[f] - x[e]) + (y[f] - y[e]) * (y[f] - y[e]);
    longest_squared = max(longest_squared, squared);
  }
  precise double twice_area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  precise double wide = half_width * half_width * longest_squared;
  if (!(twice_area * twice_area > wide)) {
    thin_seen = true;
    return;
  }
  dvec3 q[3];
  for (int c = 0; c < 3; ++c) {
    precise double nx = x[c] / half_width;
    precise double ny = y[c] / half_width;
    precise double nz = dot3(offset[c], forward) / (2.0LF * half_depth) + 0.5LF;
    q[c] = dvec3(nx, ny, nz);
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double low = axis == 2 ? 0.0LF : -1.0LF;
    if ((q[0][axis] > 1.0LF && q[1][axis] > 1.0LF && q[2][axis] > 1.0LF) ||
        (q[0][axis] < low && q[1][axis] < low && q[2][axis] < low)) {
      return;
    }
  }
  triangle(q);
  for (int e = 0; e < 3; ++e) {
    octagon(q[e]);
    strip(q[e], q[(e + 1) % 3]);
  }
}

// Amanatides and Woo's walk of the grid's cells along a -> b, as TriangleGrid::walk().
void walk(dvec3 a, dvec3 b) {
  precise dvec3 delta = b - a;
  double enter = 0.0LF, leave = 1.0LF;
  for (int axis = 0; axis < 3; ++axis) {
    precise double low = grid_origin[axis];
    precise double high = grid_origin[axis] + double(grid_dims[axis]) * grid_cell;
    if (delta[axis] == 0.0LF) {
      if (a[axis] < low || a[axis] > high) return;
      continue;
    }
    precise double t0 = (low - a[axis]) / delta[axis];
    precise double t1 = (high - a[axis]) / delta[axis];
    enter = max(enter, min(t0, t1));
    leave = min(leave, max(t0, t1));
    if (enter > leave) return;
  }
  precise dvec3 start = a + enter * delta;
  ivec3 cell, step;
  dvec3 next, increment;
  precise double length = leave - enter;
  for (int axis = 0; axis < 3; ++axis) {
    precise double position = (start[axis] - grid_origin[axis]) / grid_cell;
    cell[axis] = clamp(int(floor(position)), 0, grid_dims[axis] - 1);
    precise double d = delta[axis] / grid_cell;
    if (d > 0.0LF) {
      step[axis] = 1;
      precise double ahead = (double(cell[axis] + 1) - position) / d;
      next[axis] = ahead;
      increment[axis] = 1.0LF / d;
    } else if (d < 0.0LF) {
      step[axis] = -1;
      precise double ahead = (position - double(cell[axis])) / -d;
      next[axis] = ahead;
      increment[axis] = -1.0LF / d;
    } else {
      step[axis] = 0;
      next[axis] = increment[axis] = 1e308LF;  // never the nearest: the walk ends first
    }
  }
  for (;;) {
    const uint index = uint((cell.z * grid_dims.y + cell.y) * grid_dims.x + cell.x);
    for (uint i = offsets[index]; i < offsets[index + 1u]; ++i) candidate(entries[i]);
    const int axis = next.x < next.y ? (next.x < next.z ? 0 : 2) : (next.y < next.z ? 1 : 2);
    if (next[axis] > length) return;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= grid_dims[axis]) return;
    next[axis] += increment[axis];
  }
}

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= sample_count) return;
  const dvec3 position = dvec3(samples[6u * k], samples[6u * k + 1u], samples[6u * k + 2u]);
  const dvec3 normal = dvec3(samples[6u * k + 3u], samples[6u * k + 4u], samples[6u * k + 5u]);
  // OrthoCamera::looking_along(-normal, position, ...).
  forward = normalized(-normal);
  const dvec3 helper = abs(forward.x) < 0.9LF ? dvec3(1.0LF, 0.0LF, 0.0LF) : dvec3(0.0LF, 1.0LF, 0.0LF);
  right = normalized(cross3(forward, helper));
  up = cross3(right, forward);
  centre = position;
  best = 1.0LF;
  thin_seen = false;
  precise dvec3 a = centre - half_depth * forward;
  precise dvec3 b = centre + half_depth * forward;
  walk(a, b);
  answers[k] = Answer(float(best), thin_seen ? 1u : 0u);
}
)";

}  // namespace roving::compute_shaders
