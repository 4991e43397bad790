// A page's view of d: what every heat map page shows, whoever measured it.
#include "roving/html/distance_view.h"

#include <fmt/format.h>

namespace roving {
namespace {

// The hits' signed d over twice the colour range (the statistics' own histogram spans [-h, h],
// where h is often far wider than the data).
Histogram display_histogram(const DistanceResult& result, double range) {
  Histogram h;
  h.low = -2 * range, h.high = 2 * range;
  h.counts.assign(64, 0);
  for (std::size_t k = 0; k < result.hit.size(); ++k) {
    if (!result.hit[k]) continue;
    const double position = (result.signed_distance[k] - h.low) / (h.high - h.low) * h.counts.size();
    if (position < 0) {
      ++h.below;
    } else if (position >= h.counts.size()) {
      ++h.above;
    } else {
      ++h.counts[static_cast<std::size_t>(position)];
    }
  }
  return h;
}

}  // namespace

HtmlView distance_view(const TriangleMesh* surface, const HeatmapLayout& layout, const SampleSet& samples,
                       const DistanceResult& result, const Statistics& s, double range, double diagonal,
                       double max_error) {
  HtmlView view;
  view.surface = display_surface(surface, layout, samples, distances_or_nan(result), kHtmlMaxTriangles);
  if (result.gl) {
    for (Resolution r : result.gl->resolved_by) view.resolution.push_back(static_cast<std::uint8_t>(r));
  }
  view.range = range;
  view.diagonal = diagonal;
  view.max_error = max_error;
  const SignCounts signs = sign_counts(result);
  view.positive = signs.positive, view.negative = signs.negative, view.zero = signs.zero;
  view.no_hit = s.no_hit_count;
  if (range > 0) view.histogram = display_histogram(result, range);
  const auto length = [&](double x) { return fmt::format("{:.6g} ({:.4g}%)", x, 100 * x / diagonal); };
  const auto share = [&](std::size_t n) {
    return fmt::format("{} ({:.3g}%)", n, s.sample_count ? 100.0 * n / s.sample_count : 0.0);
  };
  view.figures = {{"USiAD (mean |d|)", length(s.usiad)},
                  {"SiAD (mean signed d)", length(s.siad)},
                  {"RMS", length(s.rms)},
                  {"STD (of signed d)", length(s.std_signed)},
                  {"max |d| (hits)", length(s.max_abs)},
                  {"|d| 95th percentile", length(s.p95)},
                  {"d > 0 (TEST outside)", share(signs.positive)},
                  {"d < 0 (TEST inside)", share(signs.negative)},
                  {"no hit within h", share(s.no_hit_count)},
                  {"query time", fmt::format("{:.3f} s", result.query_seconds)},
                  {"colour range", "\u00b1" + length(range)}};
  return view;
}

}  // namespace roving
