// Open3D 0.16's registration_ransac_based_on_correspondence with point-to-point estimation with
// scale and no checkers, as Tanks and Temples' run.py aligns a reconstruction's camera trajectory
// to the scene's: draw `sample_size` of the given pairs (with replacement), take the similarity of
// those (Umeyama), judge it by every source point's nearest target point (fitness, then RMSE), and
// stop early once enough draws were made for `confidence` at the best draw's share of given pairs
// that it brings closer than the distance. Open3D draws from one std::mt19937 shared by its OpenMP
// threads, so its result depends on their timing; here the draws are made in order on one thread,
// which is what Open3D does on one thread (OMP_NUM_THREADS=1) after utility.random.seed(seed).
#pragma once

#include <cstdint>
#include <vector>

#include "roving/reconstruction/point_registration.h"

namespace roving {

struct RansacCriteria {  // Open3D's RANSACConvergenceCriteria and its defaults
  int max_iterations = 100000;
  double confidence = 0.999;
};

// Throws roving::Error for a sample_size < 3, fewer pairs than it, a max_distance that is not
// finite and > 0, or a pair naming a point that is not there.
PointRegistration ransac_on_pairs(const std::vector<Vec3>& source, const std::vector<Vec3>& target,
                                  const PointPairs& pairs, double max_distance, int sample_size,
                                  const RansacCriteria& criteria, std::uint32_t seed);

}  // namespace roving
