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
//
// Where asked (`faces`), the same pass chooses the face the sample's hit lies on as hit_colour.h's
// hit_face() does on the CPU: each candidate's crossing of the sample's normal line by the rule
// (NormalLine::crossing()'s frame, clearly_apart() and fast_case(), operation for operation), and
// of the crossings within `face_window` of the sample's d the highest, the lowest face among
// equals. Wherever the CPU's rule would go beyond its fast case (a line within its rounding of an
// edge or corner, a crossing near the view volume's ends), or no crossing is near d, or a thin
// face is flagged, the face is left to the CPU (kFaceLeft). Compiled twice, CHOOSE_FACES defined
// 1 or 0 after the version line (compute_roving.cpp): without the faces, nothing of it is left.
inline constexpr const char* kRovingComputeShader = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { double positions[]; };
layout(std430, binding = 1) readonly buffer Corners { uint corners[]; };
layout(std430, binding = 2) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 3) readonly buffer Entries { uint entries[]; };
layout(std430, binding = 4) readonly buffer Samples { double samples[]; };  // position, normal
struct Answer {
  float depth;      // 1: no candidate covers the pixel centre
  uint thin;        // 1: a candidate is thin across the camera (the CPU decides it)
  uint face;        // the hit's face by the rule; kFaceLeft: left to the CPU
  uint unused;
  double distance;  // the rule's d on that face
};
layout(std430, binding = 5) writeonly buffer Answers { Answer answers[]; };
uniform uint sample_count;
uniform dvec3 grid_origin;
uniform double grid_cell;
uniform ivec3 grid_dims;
uniform double half_width, half_depth;
uniform dvec2 ring[8];  // the octagon's corners around a point, as the CPU computes them
// The faces' choice: asked or not; h; the window around the cameras' d (roving_tolerance());
// normal_line.cpp's constants as the CPU rounds them (u = 2^-53, 1 + 1e-9, 1 + 1e-12,
// closest_point_error_bound()'s factor, the least positive double).
uniform double max_error, face_window;
uniform double unit, slack9, slack12, allowed_per_coordinate, tiniest;
const uint kFaceLeft = 0xFFFFFFFFu;
const int kMostCrossings = 8;

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

#if CHOOSE_FACES
// The rule's frame of the sample's normal line (NormalLine's u, v: its own helper axis), and the
// crossings found so far: faces and their d, clamped into [-h, h].
dvec3 line_u, line_v, line_n;
uint crossing_face[kMostCrossings];
double crossing_d[kMostCrossings];
int crossings;
// Candidates the fast case leaves to the careful step, taken once d is known: the face, and
// where the line clearly passes through it, the fast d with its bound (else the whole line).
uint pending_face[kMostCrossings];
double pending_low[kMostCrossings], pending_high[kMostCrossings];
int pendings;
bool rule_undecided;  // a candidate the fast case does not decide: the CPU chooses the face
#endif

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

#if CHOOSE_FACES
// A double with a bound on its distance from the exact value (normal_line.cpp's Bounded): each
// operation adds its own rounding, u of its result, to the errors it inherits.
struct Bounded {
  double value, error;
};
bool exactly_zero(Bounded b) { return b.value == 0.0LF && b.error == 0.0LF; }
Bounded plus(Bounded a, Bounded b) {
  precise double r = a.value + b.value;
  precise double e = a.error + b.error + unit * abs(r);
  return Bounded(r, e);
}
Bounded minus(Bounded a, Bounded b) {
  precise double r = a.value - b.value;
  precise double e = a.error + b.error + unit * abs(r);
  return Bounded(r, e);
}
Bounded times(Bounded a, Bounded b) {
  if (exactly_zero(a) || exactly_zero(b)) return Bounded(0.0LF, 0.0LF);
  precise double r = a.value * b.value;
  precise double e = abs(a.value) * b.error + abs(b.value) * a.error + a.error * b.error + unit * abs(r) + tiniest;
  return Bounded(r, e);
}
bool unbounded;  // a divisor's bound reached 0: no bound (the CPU goes to rationals)
Bounded over(Bounded a, Bounded b) {
  if (exactly_zero(a) && !exactly_zero(b)) return Bounded(0.0LF, 0.0LF);
  precise double r = a.value / b.value;
  precise double below = abs(b.value) - b.error;
  if (!(below > 0.0LF)) {
    unbounded = true;
    return Bounded(r, 0.0LF);
  }
  precise double e = (a.error + abs(r) * b.error) / below + unit * abs(r) + tiniest;
  return Bounded(r, e);
}
bool sign_undecided;
int sign_of(Bounded b) {
  if (exactly_zero(b)) return 0;
  precise double bound = b.error * slack9;
  if (abs(b.value) > bound) return b.value > 0.0LF ? 1 : -1;
  sign_undecided = true;
  return 0;
}
Bounded exact(double v) { return Bounded(v, 0.0LF); }
Bounded dot_bounded(Bounded a[3], Bounded b[3]) { return plus(plus(times(a[0], b[0]), times(a[1], b[1])), times(a[2], b[2])); }

// The rule's careful step (normal_line.cpp's crossing_rule<Bounded>) where the line passes
// through the triangle: its d, or 0 missed, 2 where it leaves the decision to the CPU (a sign
// undecided, the line outside the triangle or edge-on: the near-miss rule, or d not known to
// `allowed`).
int careful_crossing(dvec3 p[3], double allowed, out double d) {
  d = 0.0LF;
  unbounded = false;
  sign_undecided = false;
  Bounded n[3] = Bounded[3](exact(line_n.x), exact(line_n.y), exact(line_n.z));
  const Bounded nn = dot_bounded(n, n);
  Bounded r[3][3];
  Bounded t[3];
  for (int i = 0; i < 3; ++i) {
    r[i][0] = minus(exact(p[i].x), exact(centre.x));
    r[i][1] = minus(exact(p[i].y), exact(centre.y));
    r[i][2] = minus(exact(p[i].z), exact(centre.z));
    t[i] = dot_bounded(r[i], n);
  }
  Bounded D[3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    Bounded c[3];
    c[0] = minus(times(r[i][1], r[j][2]), times(r[i][2], r[j][1]));
    c[1] = minus(times(r[i][2], r[j][0]), times(r[i][0], r[j][2]));
    c[2] = minus(times(r[i][0], r[j][1]), times(r[i][1], r[j][0]));
    D[i] = dot_bounded(c, n);
  }
  const Bounded S = plus(plus(D[0], D[1]), D[2]);
  const int area_sign = sign_of(S);
  if (sign_undecided || area_sign == 0) return 2;
  for (int i = 0; i < 3; ++i) {
    if (sign_of(D[i]) * area_sign < 0 || sign_undecided) return 2;
  }
  Bounded s = over(plus(plus(times(D[1], t[0]), times(D[2], t[1])), times(D[0], t[2])), times(S, nn));
  if (unbounded) return 2;
  const Bounded w = exact(half_depth);
  if (sign_of(plus(s, w)) < 0) return sign_undecided ? 2 : 0;
  if (sign_undecided) return 2;
  if (sign_of(minus(s, w)) > 0) return sign_undecided ? 2 : 0;
  if (sign_undecided) return 2;
  if (s.value < -max_error) s = exact(-max_error);
  if (max_error < s.value) s = exact(max_error);
  if (!(s.error <= allowed)) return 2;
  d = s.value;
  return 1;
}

// Leaves `face` to the careful step, its crossing known to lie in [low, high] (clamped into
// [-h, h]), once.
void defer_crossing(uint face, double low, double high) {
  for (int i = 0; i < pendings; ++i)
    if (pending_face[i] == face) return;
  if (pendings == kMostCrossings) {
    rule_undecided = true;
    return;
  }
  pending_face[pendings] = face;
  pending_low[pendings] = clamp(low, -max_error, max_error);
  pending_high[pendings] = clamp(high, -max_error, max_error);
  ++pendings;
}

// Keeps crossing d of `face` (once: a face is met again in another cell).
void keep_crossing(uint face, double d) {
  for (int i = 0; i < crossings; ++i)
    if (crossing_face[i] == face) return;
  if (crossings == kMostCrossings) {
    rule_undecided = true;
    return;
  }
  crossing_face[crossings] = face;
  crossing_d[crossings] = d;
  ++crossings;
}

// NormalLine::crossing() on candidate `face`, offsets r from the sample and corners p: passed
// over where clearly apart or missed, kept where through the triangle, by the fast case or the
// careful one; anything else (a line within its rounding of an edge or a corner, or passing near
// the triangle outside it) leaves the face to the CPU.
void rule_crossing(uint face, dvec3 r[3], double largest) {
  if (rule_undecided) return;
  double ku[3], kv[3], ks[3];
  for (int i = 0; i < 3; ++i) {
    ku[i] = dot3(r[i], line_u);
    kv[i] = dot3(r[i], line_v);
    ks[i] = dot3(r[i], line_n);
  }
  // clearly_apart()
  precise double across = half_width * slack12 + 32.0LF * unit * largest;
  precise double along = max_error + across;
  if ((ku[0] > across && ku[1] > across && ku[2] > across) || (ku[0] < -across && ku[1] < -across && ku[2] < -across) ||
      (kv[0] > across && kv[1] > across && kv[2] > across) || (kv[0] < -across && kv[1] < -across && kv[2] < -across) ||
      (ks[0] > along && ks[1] > along && ks[2] > along) || (ks[0] < -along && ks[1] < -along && ks[2] < -along)) {
    return;
  }
  // Offsets far from 1 in magnitude could round below the normal range, where a GPU may flush
  // them to zero (llvmpipe does): the CPU decides those.
  for (int i = 0; i < 3; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double m = abs(r[i][axis]);
      if (m != 0.0LF && (m < 1e-50LF || m > 1e50LF)) {
        rule_undecided = true;
        return;
      }
    }
  }
  precise double allowed = allowed_per_coordinate * largest;
  // fast_case()
  double R = 0.0LF;
  for (int i = 0; i < 3; ++i) R = max(R, max(abs(r[i].x), max(abs(r[i].y), abs(r[i].z))));
  precise double error_D = 64.0LF * unit * R * R;
  double D[3];
  for (int i = 0; i < 3; ++i) D[i] = dot3(cross3(r[i], r[(i + 1) % 3]), line_n);
  const bool all_positive = D[0] > error_D && D[1] > error_D && D[2] > error_D;
  const bool all_negative = D[0] < -error_D && D[1] < -error_D && D[2] < -error_D;
  if (all_positive || all_negative) {
    precise double S = D[0] + D[1] + D[2];
    const double T = max(abs(ks[0]), max(abs(ks[1]), abs(ks[2])));
    precise double s = (D[1] * ks[0] + D[2] * ks[1] + D[0] * ks[2]) / S;
    precise double error_S = 3.0LF * error_D + 2.0LF * unit * abs(S);
    precise double error_numerator = (12.0LF * unit * R + 4.0LF * unit * T) * abs(S) + 3.0LF * T * error_D;
    precise double error = (error_numerator + abs(s) * error_S) / (abs(S) - error_S) + 8.0LF * unit * abs(s);
    precise double margin = error * slack9;
    if (margin <= allowed) {
      // The view volume's ends (h widened by the tolerance: half_depth).
      precise double outer = half_depth + allowed;
      precise double inner = half_depth - allowed;
      if (s < -outer || s > outer) return;
      if (s > -inner && s < inner) {
        keep_crossing(face, clamp(s, -max_error, max_error));
        return;
      }
    }
    // The exact d is within `error` of s (the fast case's bound holds whatever `allowed`); the
    // careful step's within `allowed` of it.
    precise double reach = margin + allowed;
    precise double low = s - reach;
    precise double high = s + reach;
    defer_crossing(face, low, high);
    return;
  } else {
    const bool some_positive = D[0] > error_D || D[1] > error_D || D[2] > error_D;
    const bool some_negative = D[0] < -error_D || D[1] < -error_D || D[2] < -error_D;
    if (some_positive && some_negative) {
      // Outside: missed where every edge passes farther than the tolerance.
      precise double limit = half_width + 64.0LF * unit * R;
      precise double limit_squared = limit * limit;
      bool missed = true;
      for (int e = 0; e < 3; ++e) {
        const int q = (e + 1) % 3;
        precise double du = ku[q] - ku[e];
        precise double dv = kv[q] - kv[e];
        precise double length_squared = du * du + dv * dv;
        precise double towards = -(ku[e] * du + kv[e] * dv);
        precise double f = length_squared > 0.0LF ? clamp(towards / length_squared, 0.0LF, 1.0LF) : 0.0LF;
        precise double cu = ku[e] + f * du;
        precise double cv = kv[e] + f * dv;
        precise double distance_squared = cu * cu + cv * cv;
        if (!(distance_squared > limit_squared)) missed = false;
      }
      if (missed) return;
    }
  }
  defer_crossing(face, -max_error, max_error);
}

// The careful step on the deferred candidates that may cross the line within face_window of d.
void decide_deferred(double low, double high) {
  for (int i = 0; i < pendings && !rule_undecided; ++i) {
    if (pending_high[i] < low || pending_low[i] > high) continue;  // cannot reach the window
    const uint face = pending_face[i];
    dvec3 p[3];
    double largest = max(abs(centre.x), max(abs(centre.y), abs(centre.z)));
    for (int c = 0; c < 3; ++c) {
      p[c] = vertex(corners[3u * face + uint(c)]);
      largest = max(largest, max(abs(p[c].x), max(abs(p[c].y), abs(p[c].z))));
    }
    precise double allowed = allowed_per_coordinate * largest;
    double d;
    const int careful = careful_crossing(p, allowed, d);
    if (careful == 1) keep_crossing(face, d);
    if (careful == 2) rule_undecided = true;
  }
}

// hit_face()'s choice among the crossings, at the camera's d (as surface_roving.cpp derives it
// from the depth read back): the highest within face_window of d, the lowest face among equals.
void choose_face(float depth, out uint face, out double distance) {
  face = kFaceLeft;
  distance = 0.0LF;
  if (rule_undecided || thin_seen || depth >= 1.0f) return;
  precise double from_top = double(depth) * 2.0LF * half_depth;
  precise double unclamped = half_depth - from_top;
  const double d = clamp(unclamped, -max_error, max_error);
  precise double low = d - face_window;
  precise double high = d + face_window;
  decide_deferred(low, high);
  if (rule_undecided) return;
  for (int i = 0; i < crossings; ++i) {
    const double c = crossing_d[i];
    if (!(c >= low && c <= high)) continue;
    if (face == kFaceLeft || c > distance || (c == distance && crossing_face[i] < face)) {
      face = crossing_face[i];
      distance = c;
    }
  }
}
#endif

void candidate(uint face) {
  // The corners' offsets from the camera centre along right and up, computed once for the
  // culling, the thin test and the normalised frame (OrthoCamera::to_normalised() takes the same
  // dot products of the same offsets).
  dvec3 offset[3];
  double x[3], y[3];
#if CHOOSE_FACES
  double largest = max(abs(centre.x), max(abs(centre.y), abs(centre.z)));
#endif
  for (int c = 0; c < 3; ++c) {
    const dvec3 p = vertex(corners[3u * face + uint(c)]);
    offset[c] = p - centre;
    x[c] = dot3(offset[c], right);
    y[c] = dot3(offset[c], up);
#if CHOOSE_FACES
    largest = max(largest, max(abs(p.x), max(abs(p.y), abs(p.z))));
#endif
  }
#if CHOOSE_FACES
  // Wholly to one side of the camera by more than the rule's tolerance and the rounding of both
  // frames (each a few u of the largest coordinate): the rule misses it too, unexamined.
  precise double apart = half_width * slack12 + 64.0LF * unit * largest;
  if (!((x[0] > apart && x[1] > apart && x[2] > apart) || (x[0] < -apart && x[1] < -apart && x[2] < -apart) ||
        (y[0] > apart && y[1] > apart && y[2] > apart) || (y[0] < -apart && y[1] < -apart && y[2] < -apart))) {
    rule_crossing(face, offset, largest);
  }
#endif
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
#if CHOOSE_FACES
  // NormalLine's frame: u = n x helper, normalised; v = n x u.
  line_n = normal;
  const dvec3 line_helper = abs(normal.x) < 0.6LF ? dvec3(1.0LF, 0.0LF, 0.0LF) : dvec3(0.0LF, 1.0LF, 0.0LF);
  line_u = normalized(cross3(normal, line_helper));
  line_v = cross3(normal, line_u);
  crossings = 0;
  pendings = 0;
  rule_undecided = false;  // and a normal with a component far below 1 is left to the CPU too
  for (int axis = 0; axis < 3; ++axis)
    if (normal[axis] != 0.0LF && abs(normal[axis]) < 1e-50LF) rule_undecided = true;
#endif
  precise dvec3 a = centre - half_depth * forward;
  precise dvec3 b = centre + half_depth * forward;
  walk(a, b);
  const float depth = float(best);
  uint face = kFaceLeft;
  double distance = 0.0LF;
#if CHOOSE_FACES
  choose_face(depth, face, distance);
#endif
  answers[k] = Answer(depth, thin_seen ? 1u : 0u, face, 0u, distance);
}
)";

}  // namespace roving::compute_shaders
