// Per-channel, Y'CbCr, 6:1:1 and CIEDE2000 statistics of colour pairs.
#include "roving/core/colour_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "roving/core/colour_science.h"
#include "roving/core/error.h"

namespace roving {

double colour_psnr(double mse) {
  return mse > 0 ? 10 * std::log10(kColourPeak * kColourPeak / mse) : std::numeric_limits<double>::infinity();
}

namespace {

void require_sizes(const ColourPairs& pairs, const std::vector<std::uint8_t>& hit) {
  if (pairs.reference.size() != hit.size() || pairs.test.size() != hit.size()) {
    throw Error("colour statistics: colour pairs and hits disagree in number");
  }
}

double delta_e_of(const ColourPairs& pairs, std::size_t k) {
  return ciede2000(srgb_to_lab(pairs.reference[k].cast<double>()), srgb_to_lab(pairs.test[k].cast<double>()));
}

}  // namespace

std::vector<float> sample_delta_e(const ColourPairs& pairs, const std::vector<std::uint8_t>& hit) {
  require_sizes(pairs, hit);
  std::vector<float> delta_e(hit.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t k = 0; k < hit.size(); ++k) {
    if (hit[k]) delta_e[k] = static_cast<float>(delta_e_of(pairs, k));
  }
  return delta_e;
}

ColourStatistics compute_colour_statistics(const ColourPairs& pairs, const std::vector<std::uint8_t>& hit) {
  require_sizes(pairs, hit);
  ColourStatistics s;
  Vec3 sum_abs_rgb = Vec3::Zero(), sum_sq_rgb = Vec3::Zero();
  Vec3 sum_abs_ycbcr = Vec3::Zero(), sum_sq_ycbcr = Vec3::Zero();
  std::vector<double> delta_e;
  delta_e.reserve(hit.size());
  double delta_e_sum = 0;
  for (std::size_t k = 0; k < hit.size(); ++k) {
    if (!hit[k]) {
      ++s.no_hit;
      continue;
    }
    const Vec3 ref = pairs.reference[k].cast<double>(), test = pairs.test[k].cast<double>();
    const Vec3 rgb = test - ref;
    const Vec3 ycbcr = ycbcr_bt709(test) - ycbcr_bt709(ref);
    sum_abs_rgb += rgb.cwiseAbs();
    sum_sq_rgb += rgb.cwiseAbs2();
    sum_abs_ycbcr += ycbcr.cwiseAbs();
    sum_sq_ycbcr += ycbcr.cwiseAbs2();
    delta_e.push_back(delta_e_of(pairs, k));
    delta_e_sum += delta_e.back();
  }
  s.compared = delta_e.size();
  if (s.compared == 0) return s;
  const double n = static_cast<double>(s.compared);
  const Vec3 mse_rgb = sum_sq_rgb / n, mse_ycbcr = sum_sq_ycbcr / n;
  for (int c = 0; c < 3; ++c) {
    s.rgb[c] = {sum_abs_rgb[c] / n, std::sqrt(mse_rgb[c]), colour_psnr(mse_rgb[c])};
    s.ycbcr[c] = {sum_abs_ycbcr[c] / n, std::sqrt(mse_ycbcr[c]), colour_psnr(mse_ycbcr[c])};
  }
  s.psnr_rgb = colour_psnr(mse_rgb.mean());
  s.psnr_ycbcr_611 = colour_psnr((6 * mse_ycbcr[0] + mse_ycbcr[1] + mse_ycbcr[2]) / 8);
  s.delta_e_mean = delta_e_sum / n;
  s.delta_e_max = *std::max_element(delta_e.begin(), delta_e.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * n));
  const auto at = delta_e.begin() + (std::clamp<std::size_t>(rank, 1, delta_e.size()) - 1);
  std::nth_element(delta_e.begin(), at, delta_e.end());
  s.delta_e_p95 = *at;
  return s;
}

}  // namespace roving
