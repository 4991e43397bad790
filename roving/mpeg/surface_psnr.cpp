#include "roving/mpeg/surface_psnr.h"

#include <algorithm>

namespace roving {

SurfaceD1 surface_d1(const Statistics& statistics, const SamplingIntervals* intervals,
                     std::optional<Interval> hausdorff) {
  SurfaceD1 d;
  d.samples = statistics.sample_count;
  d.no_hits = statistics.no_hit_count;
  if (intervals) {
    // Area-uniform samples: the plain mean square estimates the surface's; RMS's interval is the
    // root of the mean square's, so squaring it gives that interval back.
    d.mse = intervals->rms.estimate * intervals->rms.estimate;
    d.mse_interval = Interval{intervals->rms.lower * intervals->rms.lower, intervals->rms.upper * intervals->rms.upper};
  } else {
    d.mse = statistics.rms_area * statistics.rms_area;
  }
  if (hausdorff) d.hausdorff = Interval{hausdorff->lower * hausdorff->lower, hausdorff->upper * hausdorff->upper};
  return d;
}

SurfaceD1 worse(const SurfaceD1& a, const SurfaceD1& b) {
  SurfaceD1 w = a.mse >= b.mse ? a : b;
  if (a.mse_interval && b.mse_interval) {
    w.mse_interval = Interval{std::max(a.mse_interval->lower, b.mse_interval->lower),
                              std::max(a.mse_interval->upper, b.mse_interval->upper)};
  }
  if (a.hausdorff && b.hausdorff) {
    w.hausdorff = Interval{std::max(a.hausdorff->lower, b.hausdorff->lower), std::max(a.hausdorff->upper, b.hausdorff->upper)};
  } else {
    w.hausdorff.reset();
  }
  return w;
}

}  // namespace roving
