// Coloured and textured models made from the real ones, for the colour tests and the benchmark's
// colour table: a smooth procedural colour field over a model's box, as vertex colours or as a
// texture.
#pragma once

#include <functional>
#include <memory>

#include "roving/core/texture.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// The procedural field at `unit`, a point's coordinates across the model's box (each in [0, 1]):
// smooth (a few periods across the box), each channel over most of [0, 255]. `phase` shifts R's
// period, a recolouring.
Colour procedural_colour(const Vec3& unit, double phase = 0);

// The field at each vertex of `mesh`, across `box` (mesh's own when empty).
std::vector<Colour> procedural_colours(const TriangleMesh& mesh, const BoundingBox& box = {});

// A side x side texture of the field over the unit square (z = 0.5), with stripes of `stripes`
// periods across it in G (0: none): detail that texture downsampling and JPEG lose.
Texture procedural_texture(int side, double phase = 0, int stripes = 0);

// `mesh` with one material of `texture` (sampled as `sampler` says), mapped by projecting along z
// onto the box's x-y square (mesh's own box when empty): u = x, v = 1 - y across it.
TriangleMesh with_planar_texture(const TriangleMesh& mesh, std::shared_ptr<const Texture> texture,
                                 const Sampler& sampler = {}, const BoundingBox& box = {});

// The field with finer detail for textures: G banded with `bands` periods along the box's diagonal
// direction (0: none), detail that texture downsampling and JPEG lose.
Colour detailed_colour(const Vec3& unit, int bands);

// A per-triangle texture atlas (MeshLab's "trivial per-triangle parametrization") baked from a
// field: each triangle gets its own square cell of side / ceil(sqrt(triangles)) texels, its
// corners one texel in from the cell's left, bottom... edges (texel coordinates (1, 1), (c - 1, 1),
// (1, c - 1) in a cell of c), and every texel of the cell is the field at the point its centre maps
// to on the triangle's plane: bilinear sampling anywhere in the triangle reads only its own
// cell, so the texture reproduces the field to its resolution. `field(p)` takes a point of the
// mesh. Throws roving::Error when a cell would be under 4 texels.
TriangleMesh with_baked_atlas(const TriangleMesh& mesh, int side,
                              const std::function<Colour(const Vec3&)>& field);

// Degraded copies of a texture: each side halved `times` times by 2 x 2 box filtering (rounded);
// each channel quantised to `bits` bits (2^bits levels over [0, 255], rounded to the nearest).
Texture downsampled(const Texture& texture, int times);
Texture quantised(const Texture& texture, int bits);
// The same quantisation of vertex colours.
std::vector<Colour> quantised(const std::vector<Colour>& colours, int bits);

}  // namespace roving
