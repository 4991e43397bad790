// Parametric surfaces: tensor-product Bezier patches (the teapot's `.bpt`), evaluated exactly for
// reference samples and tessellated, with a bound on the chordal error, as a test surface.
#pragma once

#include <string>
#include <vector>

#include "roving/sample_set.h"
#include "roving/triangle_mesh.h"

namespace roving {

struct BezierPatch {
  int degree_u = 3, degree_v = 3;
  std::vector<Vec3> control;  // (degree_u + 1) x (degree_v + 1), row i (u) by column j (v)

  const Vec3& at(int i, int j) const { return control[i * (degree_v + 1) + j]; }
  // Point and first partial derivatives at (u, v) in [0, 1]^2 (de Casteljau via Bernstein sums).
  void evaluate(double u, double v, Vec3& point, Vec3& du, Vec3& dv) const;
  // Unit normal du x dv; at a degenerate point (a collapsed edge, as at the teapot's lid and
  // bottom centres) the limit normal from just inside the patch.
  Vec3 normal(double u, double v) const;
};

struct BezierSurface {
  std::vector<BezierPatch> patches;
};

// Reads a `.bpt` file: the patch count, then per patch "m n" and (m+1)(n+1) lines "x y z".
// Throws roving::Error naming the file and line for a bad count or degree (1..16), a missing or
// malformed control point, NaN/inf, or trailing garbage.
BezierSurface read_bpt(const std::string& path);

// Makes the patches' normals (du x dv) agree across shared edges, flipping a patch by
// transposing its control net, then turns them all outward (positive flux of position through
// the surface) if most faced in. Returns the number of patches flipped. The 32-patch Utah
// teapot needs it: its patches are reflected copies, half of them inside out.
std::size_t orient_consistently(BezierSurface& surface);

// A tessellation on a uniform n x n parameter grid per patch (the same n everywhere, so shared
// patch edges meet), with n the least that keeps the chordal error below `max_error`.
// The bound per patch (Filip, Magedson and Markot 1986): for a grid cell of du x dv,
// |S - linear interpolant| <= (du^2 M_uu + 2 du dv M_uv + dv^2 M_vv) / 8, with M the bounds on the
// second partials from the control net's second differences.
struct Tessellation {
  TriangleMesh mesh;
  int cells_per_side = 0;
  double chordal_error_bound = 0;
};
Tessellation tessellate(const BezierSurface& surface, double max_error);

// Samples by exact evaluation: `faces` at the centres of a cells_per_side^2 parameter grid per
// patch (weight: the cell's area), `vertices` at its nodes, `area:N` uniform by area (rejection
// sampling against each patch's largest area element).
SampleSet bezier_samples(const BezierSurface& surface, const SampleSpec& spec, int cells_per_side);

}  // namespace roving
