// Internal: TEST's colour at the samples a GL pass resolved (the frame buffer beside the
// Z-buffer, paper Section 1). The pass gives d; where faces of M_C meet (vertices, edges, texture
// seams, face-varying colours), it does not say which of them the sample's colour comes from:
// the rasteriser keeps whichever fragment its depth rounding puts first. So the face is chosen by
// the exact rule (normal_line.h: the lowest-numbered face among those giving the chosen d) among
// the triangles that cross the sample's normal line within the pass's own error of d, and M_C is
// shaded at that point by GL as a one-pixel tile (deferred shading): the cameras' shader and
// texture sampling, at the point.
#pragma once

#include <cstdint>
#include <vector>

#include "gl_passes.h"

namespace roving {

// A resolved sample and where its colour is to be shaded: the point of M_C's triangle `face`
// nearest `point`.
struct SampleHit {
  std::uint32_t sample, face;
  Vec3 point;
};

// Sample k resolved with first-hit distance d, good to `window` (the pass's bound on its error):
// of the triangles whose crossing of k's normal line (normal_line.h, within h) reaches
// [d - window, d + window], the one first-hit chooses (the largest s, the lowest face among
// equals), at its crossing. Where none does (GL saw M_C within its tolerance of a boundary the
// exact rule does not reach), the triangle nearest the point at d.
SampleHit hit_face(const GlScene& scene, const SampleSet& samples, std::uint32_t k, double d,
                   double max_error, double window);

// Shades every hit, as one-pixel tiles drawn in batches, and hands each sample's colour to
// `coloured`. Runs on the thread that holds the GL context; needs scene.prepare_colour().
void shade_hits(GlScene& scene, const std::vector<SampleHit>& hits, const Coloured& coloured);

}  // namespace roving
