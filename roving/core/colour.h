// The colour rule (README "Colour"): REF's colour at the sample against TEST's colour at the point
// where the sample's normal line meets TEST (under closest semantics, at the closest point), the
// same correspondence that gives d. Colours are compared in their stored encoding (Colour).
#pragma once

#include <cstdint>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// `mesh`'s colour at the point of triangle `face` nearest `point`: its vertex colours interpolated
// barycentrically there (white when it has none), times its material's factor and texture, sampled
// at the texture coordinates interpolated by the same weights. Requires mesh.has_colour().
Colour colour_on_face(const TriangleMesh& mesh, std::size_t face, const Vec3& point);

// The point on TEST a sample at x with normal n and signed distance d corresponds to, to be
// placed on the hit's face: x + d n along the normal line; x itself under closest semantics (the
// face's nearest point to x is then the closest point).
inline Vec3 correspondence_point(const Vec3& x, const Vec3& n, double d, Semantics semantics) {
  return semantics == Semantics::Closest ? x : Vec3(x + d * n);
}

// REF's colour at every sample: a vertex sample takes its vertex's colour (on a textured mesh, its
// lowest face's colour at the vertex), a face or area sample its face's colour at the sample.
// Requires reference.has_colour() and samples of `reference`.
std::vector<Colour> sample_colours(const TriangleMesh& reference, const SampleSet& samples);

// Each vertex's colour by the rule: its own, or on a textured mesh its lowest face's colour at it
// (a seam gives a vertex several); NaN for a vertex no face uses. Requires mesh.has_colour().
std::vector<Colour> vertex_colours_by_rule(const TriangleMesh& mesh);

// Both colours of every sample: REF's (`reference`, one per sample) and TEST's, as a GL method
// drew it (`result.hit_colour`) or else at the correspondence on the face `result.hit_face`
// names. A no-hit has no TEST colour (NaN).
struct ColourPairs {
  std::vector<Colour> reference, test;
};
// Requires test.has_colour() and a result with hit colours or faces; throws roving::Error when it
// has neither.
ColourPairs colour_pairs(std::vector<Colour> reference, const SampleSet& samples, const TriangleMesh& test,
                         const DistanceResult& result, Semantics semantics);
// The same with REF a coloured mesh the samples were taken on.
inline ColourPairs colour_pairs(const TriangleMesh& reference, const SampleSet& samples,
                                const TriangleMesh& test, const DistanceResult& result, Semantics semantics) {
  return colour_pairs(sample_colours(reference, samples), samples, test, result, semantics);
}

}  // namespace roving
