// Bezier patches as surfaces: evaluated exactly for reference samples, and tessellated, with a
// bound on the chordal error, as a test surface.
#pragma once

#include "roving/core/bezier_patches.h"
#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// Point and first partial derivatives of `patch` at (u, v) in [0, 1]^2 (Bernstein sums).
void evaluate(const BezierPatch& patch, double u, double v, Vec3& point, Vec3& du, Vec3& dv);

// Unit normal du x dv; at a degenerate point (a collapsed edge, as at the teapot's lid and
// bottom centres) the limit normal from just inside the patch.
Vec3 normal_at(const BezierPatch& patch, double u, double v);

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
// Throws roving::Error when that needs more than kMaxTessellationTriangles.
constexpr std::size_t kMaxTessellationTriangles = std::size_t{1} << 22;  // the teapot needs 2^20
Tessellation tessellate(const BezierSurface& surface, double max_error);

// Samples by exact evaluation: `faces` at the centres of a cells_per_side^2 parameter grid per
// patch (weight: the cell's area), `vertices` at its nodes, `area:N` uniform by area (rejection
// sampling against each patch's largest area element).
SampleSet bezier_samples(const BezierSurface& surface, const SampleSpec& spec, int cells_per_side);

}  // namespace roving
