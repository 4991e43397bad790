#include "roving/mpeg/surface_psnr.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roving {
namespace {

// The mean of e^2 = ((x - c) . n)^2 over the samples (area-weighted; a no-hit at h^2), with its
// 95% interval for area-uniform samples (equal weights: the plain standard error of a mean).
void add_d2(const SampleSet& samples, const DistanceResult& result, const Correspondences& correspondences,
            const TriangleMesh& to, double max_error, bool area_uniform, SurfaceFigures& f) {
  if (result.hit_face.size() != samples.size()) return;  // a nearest-vertex baseline: no surface normal
  double sum = 0, sum_squares = 0, weight = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    double e2 = max_error * max_error;
    if (result.hit[k]) {
      const Vec3 n = to.face_normal(result.hit_face[k]);  // zero for a degenerate face: e = 0
      const double e = (samples.positions[k] - correspondences.points[k]).dot(n);
      e2 = e * e;
    }
    sum += samples.weights[k] * e2;
    sum_squares += samples.weights[k] * e2 * e2;
    weight += samples.weights[k];
  }
  f.d2_mse = sum / weight;
  const double n = double(samples.size());
  if (area_uniform && samples.size() >= 2) {
    const double variance = std::max(0.0, sum_squares / weight - f.d2_mse * f.d2_mse) * n / (n - 1);
    const double half = kZ95 * std::sqrt(variance / n);
    f.d2_mse_interval = Interval{std::max(0.0, f.d2_mse - half), f.d2_mse + half};
  }
}

}  // namespace

SurfaceFigures surface_figures(const SampleSet& samples, const DistanceResult& result,
                               const Correspondences& correspondences, const TriangleMesh& to,
                               const Statistics& statistics, const SamplingIntervals* intervals,
                               std::optional<Interval> hausdorff, double max_error) {
  SurfaceFigures f;
  f.samples = statistics.sample_count;
  f.no_hits = statistics.no_hit_count;
  if (intervals) {
    // Area-uniform samples: the plain mean square estimates the surface's; RMS's interval is the
    // root of the mean square's, so squaring it gives that interval back.
    f.d1_mse = intervals->rms.estimate * intervals->rms.estimate;
    f.d1_mse_interval =
        Interval{intervals->rms.lower * intervals->rms.lower, intervals->rms.upper * intervals->rms.upper};
  } else {
    f.d1_mse = statistics.rms_area * statistics.rms_area;
  }
  f.d2_mse = std::numeric_limits<double>::quiet_NaN();
  add_d2(samples, result, correspondences, to, max_error, intervals != nullptr, f);
  if (hausdorff) f.hausdorff = Interval{hausdorff->lower * hausdorff->lower, hausdorff->upper * hausdorff->upper};
  return f;
}

SurfaceFigures worse(const SurfaceFigures& a, const SurfaceFigures& b) {
  const auto larger = [](const std::optional<Interval>& x, const std::optional<Interval>& y) {
    return x && y ? std::optional<Interval>(Interval{std::max(x->lower, y->lower), std::max(x->upper, y->upper)})
                  : std::nullopt;
  };
  SurfaceFigures w = a.d1_mse >= b.d1_mse ? a : b;
  w.d1_mse_interval = larger(a.d1_mse_interval, b.d1_mse_interval);
  w.d2_mse = std::max(a.d2_mse, b.d2_mse);
  w.d2_mse_interval = larger(a.d2_mse_interval, b.d2_mse_interval);
  w.hausdorff = larger(a.hausdorff, b.hausdorff);
  return w;
}

}  // namespace roving
