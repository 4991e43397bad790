// Cross-checking one method against another on the same samples, with the tolerances the GL
// methods are held to, derived from the precision they report.
#pragma once

#include <cstddef>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"

namespace roving {

struct Agreement {
  std::size_t samples = 0, same_flag = 0, common_hits = 0, close = 0;
  double same_flag_fraction() const { return samples ? double(same_flag) / samples : 1.0; }
  double close_fraction() const { return common_hits ? double(close) / common_hits : 1.0; }
};

// Hit flags compared on every sample; distances on the samples both hit, within `tolerance`.
Agreement agreement(const DistanceResult& reference, const DistanceResult& result, double tolerance);

// Exact roving against an exact reference: 8 steps of float depth (the depth is rounded when
// stored and when interpolated, 2^-24 of the 2h range each) plus the rasteriser's subpixel
// snapping (1/256 pixel in llvmpipe: the central ray moves by up to w / 128 across, w the
// camera half-width) times a depth slope of 10 (surfaces up to 84 degrees from facing the
// camera; steeper ones are the 0.5% the gate leaves).
double roving_tolerance(const GlReport& gl);

// A view-resolved sample against an exact reference, for a sample whose normal is `alpha` from
// its view direction, measured as d: nearest-pixel or interpolated reading moves the read point
// up to p / sqrt(2) across (p the view pixel; bilinear is exact on a plane but not across a
// crease), a depth slope of tan(alpha + 30 degrees) for M_C within 30 degrees of M_R's
// orientation; the cosine correction is exact for M_C parallel to M_R and off by
// |d| tan(alpha) tan(30 degrees) at that tilt; plus 16 steps of view depth.
double view_tolerance(const GlReport& gl, double alpha, double d);

struct ViewAgreement {
  std::size_t resolved = 0, within = 0;
  double within_fraction() const { return resolved ? double(within) / resolved : 1.0; }
};

// The samples `result` resolved by a view, against `reference` within view_tolerance (a sample
// the reference missed counts as outside).
ViewAgreement view_agreement(const DistanceResult& reference, const DistanceResult& result,
                             const SampleSet& samples, const GlReport& gl);

}  // namespace roving
