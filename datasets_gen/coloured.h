// Coloured and textured models made from the real ones, for the colour tests and the benchmark's
// colour table: a smooth procedural colour field over a model's box, as vertex colours or as a
// texture.
#pragma once

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

}  // namespace roving
