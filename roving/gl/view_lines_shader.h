// The GLSL source of viewpoint sampling's lookup in a compute pass (view_lines.cpp).
#pragma once

namespace roving::compute_shaders {

// One invocation per sample of a view: viewpoint_sampling.cpp's ViewLine::first_crossing() on
// the view's depth image as it lies on the GPU (copied there from the depth buffer, the rectangle
// drawn alone), operation for operation in double (`precise`: no fused multiply-adds): the
// march of the sample's normal line from t = h down to -h, the secant refinement, the flatness
// check and the one-facet plane. Each answer is d, or not accepted (the cameras decide).
inline constexpr const char* kViewLinesComputeShader = R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Depth { float depth[]; };     // the rectangle, row by row
layout(std430, binding = 1) readonly buffer Samples { double samples[]; };  // position, normal
struct Answer {
  double d;
  uint accepted;
  uint unused;
};
layout(std430, binding = 2) writeonly buffer Answers { Answer answers[]; };
uniform uint sample_count;
uniform ivec4 rect;  // x0, y0, x1, y1: the pixels the depth buffer holds
uniform int resolution;
uniform dvec3 centre, right, up, forward;
uniform dvec3 half_extents;  // half width, half height, half depth
uniform double h, smooth_span, depth_scale, crease_limit, min_distance, noise;

double dot3(dvec3 a, dvec3 b) {
  precise double d = a.x * b.x + a.y * b.y + a.z * b.z;
  return d;
}

dvec3 to_normalised(dvec3 p) {
  precise dvec3 q = p - centre;
  precise double x = dot3(q, right) / half_extents.x;
  precise double y = dot3(q, up) / half_extents.y;
  precise double z = dot3(q, forward) / (2.0LF * half_extents.z) + 0.5LF;
  return dvec3(x, y, z);
}

dvec3 along(dvec3 x, dvec3 n, double t) {
  precise dvec3 p = x + t * n;
  return p;
}

// The pixel (i, j) of the image; 1 (nothing drawn) outside the rectangle read.
double at(int i, int j) {
  if (i < rect.x || j < rect.y || i >= rect.z || j >= rect.w) return 1.0LF;
  return double(depth[(j - rect.y) * (rect.z - rect.x) + (i - rect.x)]);
}

// Seen minus own depth at x + t n; `valid` false where the view is not one smooth drawn patch.
double f(dvec3 x, dvec3 n, double t, out bool valid) {
  valid = true;
  const dvec3 q = to_normalised(along(x, n, t));
  precise double u = (0.5LF * q.x + 0.5LF) * double(resolution) - 0.5LF;
  precise double v = (0.5LF * q.y + 0.5LF) * double(resolution) - 0.5LF;
  const int i0 = int(floor(u)), j0 = int(floor(v));
  if (i0 < 0 || j0 < 0 || i0 + 1 >= resolution || j0 + 1 >= resolution) {
    valid = false;
    return 0.0LF;
  }
  const double z00 = at(i0, j0), z10 = at(i0 + 1, j0), z01 = at(i0, j0 + 1), z11 = at(i0 + 1, j0 + 1);
  const double low = min(min(z00, z10), min(z01, z11)), high = max(max(z00, z10), max(z01, z11));
  precise double fx = u - double(i0);
  precise double fy = v - double(j0);
  precise double seen = (1.0LF - fy) * ((1.0LF - fx) * z00 + fx * z10) + fy * ((1.0LF - fx) * z01 + fx * z11);
  precise double span = high - low;
  if (high >= 1.0LF || span > smooth_span) {
    if (low >= 1.0LF) return 1.0LF;
    precise double ahead = low - q.z;
    if (q.z < low) return ahead;
    valid = false;
    return 0.0LF;
  }
  precise double difference = seen - q.z;
  return difference;
}

double refine(dvec3 x, dvec3 n, double t_low, double f_low, double t_high, double f_high) {
  for (int iteration = 0; iteration < 4 && f_high - f_low > 0.0LF; ++iteration) {
    precise double t = t_high - f_high * (t_high - t_low) / (f_high - f_low);
    bool valid;
    const double f_t = f(x, n, t, valid);
    if (!valid) break;
    if (f_t <= 0.0LF) {
      t_low = t, f_low = f_t;
    } else {
      t_high = t, f_high = f_t;
    }
  }
  precise double secant = t_high - f_high * (t_high - t_low) / (f_high - f_low);
  return f_high - f_low > 0.0LF ? secant : t_low;
}

bool flat_around(dvec3 q, double limit) {
  precise double u = (0.5LF * q.x + 0.5LF) * double(resolution) - 0.5LF;
  precise double v = (0.5LF * q.y + 0.5LF) * double(resolution) - 0.5LF;
  const int i0 = int(floor(u)) - 1, j0 = int(floor(v)) - 1;
  if (i0 < 0 || j0 < 0 || i0 + 3 >= resolution || j0 + 3 >= resolution) return false;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      if (at(i0 + a, j0 + b) >= 1.0LF) return false;
    }
  }
  for (int a = 0; a < 4; ++a) {
    for (int b = 1; b < 3; ++b) {
      precise double across_x = at(i0 + b - 1, j0 + a) - 2.0LF * at(i0 + b, j0 + a) + at(i0 + b + 1, j0 + a);
      if (abs(across_x) > limit) return false;
      precise double across_y = at(i0 + a, j0 + b - 1) - 2.0LF * at(i0 + a, j0 + b) + at(i0 + a, j0 + b + 1);
      if (abs(across_y) > limit) return false;
    }
  }
  return true;
}

int window_i0, window_j0;
double z(int i, int j) { return at(window_i0 + i, window_j0 + j); }
double gx, gy, c;
double plane(double i, double j) {
  precise double p = c + gx * i + gy * j;
  return p;
}
bool on_plane(int i, int j) {
  precise double off = z(i, j) - plane(double(i), double(j));
  return abs(off) <= noise;
}
dvec3 window_of(dvec3 q) {
  precise double wx = (0.5LF * q.x + 0.5LF) * double(resolution) - 0.5LF - double(window_i0);
  precise double wy = (0.5LF * q.y + 0.5LF) * double(resolution) - 0.5LF - double(window_j0);
  return dvec3(wx, wy, q.z);
}

bool on_one_facet(dvec3 x, dvec3 n, dvec3 at_q, out double t_out) {
  precise double u = (0.5LF * at_q.x + 0.5LF) * double(resolution) - 0.5LF;
  precise double v = (0.5LF * at_q.y + 0.5LF) * double(resolution) - 0.5LF;
  window_i0 = int(floor(u)) - 1, window_j0 = int(floor(v)) - 1;
  precise double twist = z(1, 1) - z(2, 1) - z(1, 2) + z(2, 2);
  if (abs(twist) > noise) return false;
  precise double gx_ = 0.5LF * (z(2, 1) - z(1, 1) + z(2, 2) - z(1, 2));
  precise double gy_ = 0.5LF * (z(1, 2) - z(1, 1) + z(2, 2) - z(2, 1));
  gx = gx_, gy = gy_;
  precise double c_ = 0.25LF * (z(1, 1) + z(2, 1) + z(1, 2) + z(2, 2)) - 1.5LF * (gx + gy);
  c = c_;
  const bool along_x = (on_plane(0, 1) && on_plane(0, 2)) || (on_plane(3, 1) && on_plane(3, 2));
  const bool along_y = (on_plane(1, 0) && on_plane(2, 0)) || (on_plane(1, 3) && on_plane(2, 3));
  if (!along_x || !along_y) return false;
  const dvec3 w0 = window_of(to_normalised(x));
  precise dvec3 dw = window_of(to_normalised(along(x, n, 1.0LF))) - w0;
  precise double rate = gx * dw.x + gy * dw.y - dw.z;
  if (rate == 0.0LF) return false;
  precise double t = (w0.z - plane(w0.x, w0.y)) / rate;
  precise dvec3 w = w0 + t * dw;
  if (!(w.x >= 1.0LF && w.x <= 2.0LF && w.y >= 1.0LF && w.y <= 2.0LF)) return false;
  t_out = t;
  return true;
}

// ViewLine::first_crossing(): true with d where the view resolves the sample.
bool first_crossing(dvec3 x, dvec3 n, out double d) {
  const dvec3 a = to_normalised(along(x, n, h)), b = to_normalised(along(x, n, -h));
  precise double dx = a.x - b.x;
  precise double dy = a.y - b.y;
  precise double pixels = 0.5LF * double(resolution) * sqrt(dx * dx + dy * dy);
  const int steps = max(2, int(ceil(2.0LF * pixels)));
  double t_previous = h;
  bool valid;
  double f_previous = f(x, n, h, valid);
  if (!valid || f_previous < 0.0LF) return false;
  for (int k = 1; k <= steps; ++k) {
    precise double t = h - 2.0LF * h * double(k) / double(steps);
    const double f_now = f(x, n, t, valid);
    if (!valid) return false;
    if (f_now <= 0.0LF) {
      const double s = refine(x, n, t, f_now, t_previous, f_previous);
      precise double relative = 0.1LF * abs(s) / depth_scale;
      const double limit = min(crease_limit, relative);
      const dvec3 at_s = to_normalised(along(x, n, s));
      if (flat_around(at_s, limit)) {
        if (abs(s) < min_distance) return false;
        d = s;
        return true;
      }
      if (limit == crease_limit || !flat_around(at_s, crease_limit)) return false;
      double on_facet;
      if (!on_one_facet(x, n, at_s, on_facet) || abs(on_facet) < min_distance) return false;
      d = on_facet;
      return true;
    }
    t_previous = t;
    f_previous = f_now;
  }
  return false;
}

void main() {
  const uint k = gl_GlobalInvocationID.x;
  if (k >= sample_count) return;
  const dvec3 x = dvec3(samples[6u * k], samples[6u * k + 1u], samples[6u * k + 2u]);
  const dvec3 n = dvec3(samples[6u * k + 3u], samples[6u * k + 4u], samples[6u * k + 5u]);
  double d = 0.0LF;
  const bool accepted = first_crossing(x, n, d);
  answers[k] = Answer(accepted ? d : 0.0LF, accepted ? 1u : 0u, 0u);
}
)";

}  // namespace roving::compute_shaders
