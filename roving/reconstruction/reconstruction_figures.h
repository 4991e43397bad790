// The figures surface-reconstruction papers publish (accuracy, completeness, Chamfer distance,
// precision, recall and F-score at a threshold tau, normal consistency), computed exactly from the
// two directions' per-sample correspondences: REF is the ground truth, TEST the reconstruction.
// Every mean is area-weighted over the samples (each sample stands for its area of the surface),
// so the figures integrate over the surfaces rather than count points; with area-uniform samples
// each figure has a 95% interval (normal approximation, as the distance means have).
#pragma once

#include <optional>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// One direction's samples on `from`, measured against `to` (closest semantics for the published
// meaning); `to`'s faces give the normal at each correspondence where the result names them.
// `region`, where given, marks the samples the figures count (1) and leaves out the rest (0): the
// figures are then those of that region of `from` (area-uniform samples stay uniform within it).
struct CorrespondenceSet {
  const SampleSet* samples = nullptr;
  const DistanceResult* result = nullptr;
  const TriangleMesh* to = nullptr;
  const std::vector<std::uint8_t>* region = nullptr;
};

// An estimate and, for area-uniform samples, its 95% interval (NaN bounds otherwise).
struct Estimate {
  double value = 0, lower = 0, upper = 0;
};

// One direction: the area-weighted mean, median and RMS of |d| over the hits, the share of the
// area within each threshold (a no-hit is beyond every threshold), and the mean |n . n'| of the
// sample's normal and the surface's normal at its correspondence (NaN where faces are not known).
struct DirectionFigures {
  Estimate mean, rms;
  double median = 0;
  std::vector<Estimate> within;  // per threshold
  Estimate normal_consistency;
  std::size_t hits = 0, no_hits = 0;
};

struct ReconstructionFigures {
  std::vector<double> thresholds;  // tau, model units
  DirectionFigures accuracy;       // TEST (reconstruction) to REF (ground truth)
  DirectionFigures completeness;   // REF to TEST
  // Chamfer distance in its published variants: the mean of the two means (DTU's "overall",
  // Tanks and Temples), their sum (Occupancy Networks' L1 times 2, point-cloud-utils), and the
  // squared forms (mean of the two mean squared distances; their sum).
  double chamfer_mean = 0, chamfer_sum = 0, chamfer_squared_mean = 0, chamfer_squared_sum = 0;
  // chamfer_mean and chamfer_sum with 95% intervals (NaN bounds where the directions have none):
  // the two directions' samples are independent, so their half-widths add in quadrature.
  Estimate chamfer_mean_estimate, chamfer_sum_estimate;
  // Per threshold: precision (accuracy's share within tau), recall (completeness's), and their
  // harmonic mean F (0 where both are 0).
  std::vector<double> precision, recall, f_score;
  // Per threshold, F with its 95% interval from precision's and recall's by the delta method
  // (independent samples; dF/dP = 2 R^2 / (P + R)^2, dF/dR = 2 P^2 / (P + R)^2).
  std::vector<Estimate> f_score_estimate;
  double normal_consistency = 0;  // the mean of both directions'
  // Per threshold, where both surfaces are triangles measured with closest semantics: precision's
  // and recall's certified bounds as shares of area (reference_embree/certified_area_within.h) and
  // F's from them (F grows with P and with R). Empty otherwise.
  struct Bounds {
    double lower = 0, upper = 0;
  };
  std::vector<Bounds> precision_certified, recall_certified, f_score_certified;
};

// The harmonic mean of precision p and recall r; 0 where both are 0.
double f_score(double p, double r);

// Sets f's certified bounds from precision's and recall's, one per threshold each.
void set_certified_shares(ReconstructionFigures& f, std::vector<ReconstructionFigures::Bounds> precision,
                          std::vector<ReconstructionFigures::Bounds> recall);

// `reference_to_test` measured REF's samples against TEST, `test_to_reference` TEST's against REF.
// Throws roving::Error for a threshold that is not finite and > 0.
ReconstructionFigures reconstruction_figures(const CorrespondenceSet& reference_to_test,
                                             const CorrespondenceSet& test_to_reference,
                                             const std::vector<double>& thresholds, bool area_uniform);

// Each hit's |n . n'|: the sample's normal against the normal of the face its correspondence lies
// on (0 for a no-hit or a degenerate face); empty where the result names no faces.
std::vector<double> normal_agreement(const CorrespondenceSet& set);

// What the figures are computed from, per sample: d, hit, the area it stands for, and
// normal_agreement's value (empty: unknown). A merge of shards has these without the models.
struct SampleFigures {
  const std::vector<double>* signed_distance = nullptr;
  const std::vector<std::uint8_t>* hit = nullptr;
  const std::vector<double>* weights = nullptr;
  const std::vector<double>* agreement = nullptr;
  const std::vector<std::uint8_t>* region = nullptr;  // as CorrespondenceSet's
};

// The same figures from the per-sample arrays.
ReconstructionFigures reconstruction_figures(const SampleFigures& reference_to_test,
                                             const SampleFigures& test_to_reference,
                                             const std::vector<double>& thresholds, bool area_uniform);

}  // namespace roving
