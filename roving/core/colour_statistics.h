// Statistics of per-sample colour differences (README "Colour"): what MPEG's metrics report
// (per-channel PSNR in R'G'B' and BT.709 Y'CbCr, and the 6:1:1 Y'CbCr PSNR) and a perceptual
// figure (CIEDE2000).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "roving/core/colour.h"

namespace roving {

// Colour PSNR's peak: the largest 8-bit code value (MPEG's mmetric; pc_error's peak 1 on [0, 1]
// gives the same PSNR).
constexpr double kColourPeak = 255;

// Every figure is NaN (no figure, null in JSON) until a hit is compared.
constexpr double kNoFigure = std::numeric_limits<double>::quiet_NaN();

struct ChannelErrors {
  double mean_abs = kNoFigure, rms = kNoFigure;
  double psnr = kNoFigure;  // 10 log10(peak^2 / MSE); +infinity where the colours agree exactly
};

// Plain means over the samples that have both colours (the hits), as MPEG's metrics average
// over points; a no-hit has no TEST colour and is counted apart.
struct ColourStatistics {
  std::size_t compared = 0, no_hit = 0;
  std::array<ChannelErrors, 3> rgb;    // R', G', B'
  std::array<ChannelErrors, 3> ycbcr;  // Y', Cb, Cr (BT.709)
  double psnr_rgb = kNoFigure;         // on the mean of the three channels' MSE
  double psnr_ycbcr_611 = kNoFigure;   // MPEG: on (6 MSE_Y + MSE_Cb + MSE_Cr) / 8
  double delta_e_mean = kNoFigure, delta_e_p95 = kNoFigure,
         delta_e_max = kNoFigure;  // CIEDE2000; p95 nearest-rank
};

// Each sample's CIEDE2000 delta E between its two colours; NaN where it has no hit. Throws
// roving::Error on sizes that disagree.
std::vector<float> sample_delta_e(const ColourPairs& pairs, const std::vector<std::uint8_t>& hit);

// Throws roving::Error on sizes that disagree.
ColourStatistics compute_colour_statistics(const ColourPairs& pairs, const std::vector<std::uint8_t>& hit);

// 10 log10(peak^2 / mse), +infinity for mse == 0.
double colour_psnr(double mse);

}  // namespace roving
