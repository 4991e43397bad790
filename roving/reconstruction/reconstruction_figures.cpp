// Reconstruction figures from per-sample correspondences (reconstruction_figures.h).
#include "roving/reconstruction/reconstruction_figures.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "roving/core/error.h"

namespace roving {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The weighted mean of `values` (over `use`), with its 95% interval when the samples are
// area-uniform (equal weights: the plain standard error of a mean of independent draws).
Estimate weighted_mean(const std::vector<double>& values, const std::vector<double>& weights,
                       const std::vector<std::uint8_t>& use, bool area_uniform) {
  double sum = 0, weight = 0, sum_squares = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!use[k]) continue;
    sum += weights[k] * values[k];
    sum_squares += weights[k] * values[k] * values[k];
    weight += weights[k];
    ++n;
  }
  if (n == 0 || !(weight > 0)) return {kNaN, kNaN, kNaN};
  const double mean = sum / weight;
  if (!area_uniform || n < 2) return {mean, kNaN, kNaN};
  const double variance = std::max(0.0, sum_squares / weight - mean * mean) * double(n) / double(n - 1);
  const double half = 1.96 * std::sqrt(variance / double(n));
  return {mean, mean - half, mean + half};
}

// An estimate of `value` from two independent estimates a and b with symmetric 95% intervals,
// where d value / d a = da and d value / d b = db: the delta method's interval (the normal
// approximation's 1.96 cancels between the half-widths).
Estimate combined(double value, const Estimate& a, double da, const Estimate& b, double db) {
  if (std::isnan(a.lower) || std::isnan(b.lower)) return {value, kNaN, kNaN};
  const double half = std::hypot(da * (a.upper - a.lower) / 2, db * (b.upper - b.lower) / 2);
  return {value, value - half, value + half};
}

DirectionFigures direction_figures(const SampleFigures& set, const std::vector<double>& thresholds,
                                   bool area_uniform) {
  const std::vector<double>& weights = *set.weights;
  const std::size_t count = set.signed_distance->size();
  DirectionFigures f;
  std::vector<double> distance(count, 0), squared(count, 0);
  if (set.region && set.region->size() != count) {
    throw Error(fmt::format("reconstruction figures: a region of {} samples for {} samples", set.region->size(), count));
  }
  // `counted`: the region's samples (every sample without one); only they enter the figures.
  std::vector<std::uint8_t> hit(count, 0), counted(count, 1);
  for (std::size_t k = 0; k < count; ++k) {
    if (set.region && !(*set.region)[k]) {
      counted[k] = 0;
      continue;
    }
    hit[k] = (*set.hit)[k];
    distance[k] = std::abs((*set.signed_distance)[k]);
    squared[k] = distance[k] * distance[k];
    (hit[k] ? f.hits : f.no_hits) += 1;
  }
  f.mean = weighted_mean(distance, weights, hit, area_uniform);
  const Estimate mean_square = weighted_mean(squared, weights, hit, area_uniform);
  f.rms = {std::sqrt(mean_square.value),
           std::isnan(mean_square.lower) ? kNaN : std::sqrt(std::max(0.0, mean_square.lower)),
           std::sqrt(mean_square.upper)};
  // The weighted median: the smallest |d| below which half the hits' area lies.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < count; ++k) {
    if (hit[k]) order.push_back(k);
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
  double total = 0;
  for (std::size_t k : order) total += weights[k];
  double below = 0;
  f.median = kNaN;
  for (std::size_t k : order) {
    below += weights[k];
    if (below >= 0.5 * total) {
      f.median = distance[k];
      break;
    }
  }
  // The share of the area (the region's; no-hits included, as beyond any threshold) within each tau.
  for (const double tau : thresholds) {
    std::vector<double> inside(count, 0);
    for (std::size_t k = 0; k < count; ++k) inside[k] = hit[k] && distance[k] <= tau ? 1 : 0;
    f.within.push_back(weighted_mean(inside, weights, counted, area_uniform));
  }
  // Normal consistency where the correspondence's face is known.
  f.normal_consistency = set.agreement && set.agreement->size() == count
                             ? weighted_mean(*set.agreement, weights, hit, area_uniform)
                             : Estimate{kNaN, kNaN, kNaN};
  return f;
}

}  // namespace

std::vector<double> normal_agreement(const CorrespondenceSet& set) {
  const SampleSet& samples = *set.samples;
  const DistanceResult& result = *set.result;
  const std::size_t count = samples.size();
  if (result.hit_face.size() != count) return {};
  std::vector<double> agreement(count, 0);
  for (std::size_t k = 0; k < count; ++k) {
    if (!result.hit[k]) continue;
    const Triangle& t = set.to->triangles()[result.hit_face[k]];
    const Vec3& a = set.to->positions()[t[0]];
    const Vec3 n = (set.to->positions()[t[1]] - a).cross(set.to->positions()[t[2]] - a);
    agreement[k] = n.norm() > 0 ? std::abs(samples.normals[k].dot(n.normalized())) : 0;
  }
  return agreement;
}

ReconstructionFigures reconstruction_figures(const CorrespondenceSet& reference_to_test,
                                             const CorrespondenceSet& test_to_reference,
                                             const std::vector<double>& thresholds, bool area_uniform) {
  const std::vector<double> forward = normal_agreement(reference_to_test),
                            backward = normal_agreement(test_to_reference);
  const auto arrays = [](const CorrespondenceSet& set, const std::vector<double>& agreement) {
    return SampleFigures{&set.result->signed_distance, &set.result->hit, &set.samples->weights, &agreement, set.region};
  };
  return reconstruction_figures(arrays(reference_to_test, forward), arrays(test_to_reference, backward), thresholds,
                                area_uniform);
}

ReconstructionFigures reconstruction_figures(const SampleFigures& reference_to_test,
                                             const SampleFigures& test_to_reference,
                                             const std::vector<double>& thresholds, bool area_uniform) {
  for (const double tau : thresholds) {
    if (!(tau > 0) || !std::isfinite(tau)) {
      throw Error(fmt::format("--threshold: expected a finite distance > 0, found {}", tau));
    }
  }
  ReconstructionFigures r;
  r.thresholds = thresholds;
  r.completeness = direction_figures(reference_to_test, thresholds, area_uniform);
  r.accuracy = direction_figures(test_to_reference, thresholds, area_uniform);
  const double a = r.accuracy.mean.value, c = r.completeness.mean.value;
  const double a2 = r.accuracy.rms.value * r.accuracy.rms.value,
               c2 = r.completeness.rms.value * r.completeness.rms.value;
  r.chamfer_mean = (a + c) / 2, r.chamfer_sum = a + c;
  r.chamfer_squared_mean = (a2 + c2) / 2, r.chamfer_squared_sum = a2 + c2;
  r.chamfer_mean_estimate = combined(r.chamfer_mean, r.accuracy.mean, 0.5, r.completeness.mean, 0.5);
  r.chamfer_sum_estimate = combined(r.chamfer_sum, r.accuracy.mean, 1, r.completeness.mean, 1);
  for (std::size_t i = 0; i < thresholds.size(); ++i) {
    const double p = r.accuracy.within[i].value, q = r.completeness.within[i].value;
    r.precision.push_back(p);
    r.recall.push_back(q);
    r.f_score.push_back(f_score(p, q));
    const double sum_squared = (p + q) * (p + q);
    r.f_score_estimate.push_back(combined(r.f_score.back(), r.accuracy.within[i], p + q > 0 ? 2 * q * q / sum_squared : 0,
                                          r.completeness.within[i], p + q > 0 ? 2 * p * p / sum_squared : 0));
  }
  r.normal_consistency = (r.accuracy.normal_consistency.value + r.completeness.normal_consistency.value) / 2;
  return r;
}

double f_score(double p, double r) { return p + r > 0 ? 2 * p * r / (p + r) : 0; }

void set_certified_shares(ReconstructionFigures& f, std::vector<ReconstructionFigures::Bounds> precision,
                          std::vector<ReconstructionFigures::Bounds> recall) {
  if (precision.size() != f.thresholds.size() || recall.size() != f.thresholds.size()) {
    throw Error(fmt::format("certified shares: expected {} thresholds, found {} and {}", f.thresholds.size(),
                            precision.size(), recall.size()));
  }
  f.f_score_certified.clear();
  for (std::size_t k = 0; k < f.thresholds.size(); ++k) {
    f.f_score_certified.push_back({f_score(precision[k].lower, recall[k].lower), f_score(precision[k].upper, recall[k].upper)});
  }
  f.precision_certified = std::move(precision);
  f.recall_certified = std::move(recall);
}

}  // namespace roving
