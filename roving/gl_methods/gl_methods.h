// The paper's methods on OpenGL (Sections 4.1-4.3): exact surface roving, viewpoint sampling and
// the cooperative method, each a DistanceMethod with first-hit (paper) semantics.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/gl/depth_renderer.h"

namespace roving {

struct GlMethodOptions {
  GlBackend backend = default_gl_backend();
  int views_h = 24, views_v = 12;  // viewpoint sampling: H longitudes x V latitudes (15 degrees)
  int resolution = 1024;           // side of a viewpoint-sampling view, pixels
  // How a view is read at a sample (measured in results/view-reading.md): bilinear between the
  // four nearest pixel centres when they lie on one smooth patch, else the nearest pixel; and
  // whether the along-view difference is turned into the along-normal one by cos(n, view).
  bool bilinear = true;
  bool cosine_correction = true;
  // Instead of both: march the sample's normal line across the view's depth image to its first
  // crossing of the visible surface (viewpoint_sampling.cpp), accepted only where that is
  // certainly the line's first crossing of M_C. The default: its error is bounded on every
  // kind of pair (results/gl-accuracy.md), where the cosine correction's is not.
  bool normal_line = true;
  // Draw each view only where its samples read: the triangles that reach those pixels, scissored
  // to their rectangle (view_footprint.h). Every pixel read keeps its depth, so results are
  // identical (tests/gl_methods_test.cpp); off only to show that.
  bool cull_views = true;
  // `--views auto`: the cooperative method starts with the cameras, timed as they go, and turns
  // to views only if the fullest direction's cameras would cost more than grouping the samples
  // by direction and a first draw; then it draws a direction's view only while it is expected to
  // cost less than the per-sample cameras it would save, and the other samples go to cameras.
  // Otherwise it is exact roving, in the same pipeline. Its observations are reported as they
  // happened.
  bool auto_views = false;
  // `--camera-geometry gpu`: surface roving's cameras get their triangles in the camera's frame,
  // and the edges and corners widened, in a compute shader (in double, from storage buffers, one
  // invocation per candidate triangle) rather than on the CPU; the CPU only finds the
  // candidates. The same geometry either way (tests/gl_methods_test.cpp); which is faster
  // depends on the hardware (results/gpu-cameras.md).
  // `--camera-geometry compute`: nothing drawn; each camera's depth is evaluated in a compute
  // pass, one invocation per sample walking TEST's grid on the GPU (compute_roving_shader.h),
  // under the raster path's coverage; faces thin across a camera go to the CPU's rule.
  CameraGeometry camera_geometry = CameraGeometry::Cpu;
};

// Parses "HxV" (each 1..720); throws roving::Error naming `--views` otherwise.
void parse_views(const std::string& text, int& h, int& v);
// Parses "HxV", "auto" (auto_views over 24x12 directions) or "auto:HxV" into `options`.
void parse_views(const std::string& text, GlMethodOptions& options);

// The H x V view directions, unit vectors at the centres of a longitude-latitude grid:
// longitude 360 (i + 0.5) / H, latitude -90 + 180 (j + 0.5) / V degrees; index j * H + i.
std::vector<Vec3> view_directions(int h, int v);

// The 6 axis directions +x, -x, +y, -y, +z, -z: the views of a voxel reference (Section 4.3).
std::vector<Vec3> axis_directions();

// The index of the direction nearest n (the largest dot product, the lowest index among equal
// ones), as comparing n with every direction gives. Where `directions` is view_directions(h, v)
// only the cells around n's own are compared; h = v = 0 (the axes, say) compares them all.
std::uint32_t nearest_direction(const std::vector<Vec3>& directions, int h, int v, const Vec3& n);

// The directions of a run's views and their nearest: the 6 axes when `axes` (the views of a
// voxel reference), else the H x V grid.
struct ViewGrid {
  ViewGrid(bool axes, int h, int v)
      : directions(axes ? axis_directions() : view_directions(h, v)), h(axes ? 0 : h), v(axes ? 0 : v) {}
  std::uint32_t nearest(const Vec3& n) const { return nearest_direction(directions, h, v, n); }

  std::vector<Vec3> directions;
  int h, v;
};

// Whether every normal is an axis, as a voxel reference's are: then the 6 axis views suffice
// (Section 4.3).
bool axis_normals(const SampleSet& samples);

// Exact surface roving: one orthographic camera per sample, its view volume the box of
// half-height h about the sample along its normal and one pixel across, whose centre is the
// central ray. Cameras are one-pixel tiles of one framebuffer, many per draw; each tile draws only
// the triangles a uniform grid finds along its segment. The depth read back is the first
// crossing of the central ray (rasterisation's pixel-centre rule is watertight).
std::unique_ptr<DistanceMethod> make_surface_roving(const GlMethodOptions& options);

// Viewpoint sampling alone: samples go to the nearest of H x V directions; per direction with
// samples, M_C is drawn whole into a resolution^2 view looking against that direction, and a
// sample is accepted when the depth at its pixel is within h of its own (the paper's occlusion
// test). d is the along-view difference times cos(normal, direction). Others are unresolved
// (no hit, counted as h).
std::unique_ptr<DistanceMethod> make_viewpoint_sampling(const GlMethodOptions& options);

// Viewpoint sampling, then surface roving for the samples no view accepted.
std::unique_ptr<DistanceMethod> make_cooperative(const GlMethodOptions& options);

}  // namespace roving
