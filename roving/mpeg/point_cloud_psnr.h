// MPEG's geometry and colour figures for two point clouds, defined as its pc_error
// (mpeg-pcc-dmetric release 0.14, default options) computes them, so that a codec paper's D1 / D2
// PSNR comes out of roving as it comes out of pc_error (docs/mpeg.md lists every rule and where we
// part from it):
// - each point of one cloud is paired with its nearest point of the other (squared Euclidean
//   distance in double on single-precision coordinates);
// - D1 (point-to-point): that squared distance; D2 (point-to-plane): its squared projection on the
//   other point's normal, averaged over the nearest points at the same distance (consecutive
//   squared distances within 1e-8 of each other, among up to 30 neighbours);
// - normals come from A alone: B -> A uses A's normals; A -> B uses A's normals carried onto B
//   (each A point's normal added to its nearest B points, exact ties all; averaged, not
//   normalised; a B point no A point reached takes the mean of its nearest A points' normals);
//   without normals in A there is no D2;
// - colour: the nearest points' 8-bit colours averaged (rounded) over the same ties, compared in
//   BT.709 Y'CbCr on [0, 1] (peak 1) and in RGB (peak 255);
// - MSE is the mean over the cloud's points; Hausdorff the largest squared distance; PSNR
//   10 log10(3 p^2 / MSE) for geometry with p the peak: `resolution` when given, else the largest
//   distance from a point of A to its nearest other point of A (pc_error's default);
// - symmetric: the worse direction (largest MSE, smallest PSNR).
#pragma once

#include <array>
#include <optional>
#include <string>

#include "roving/mpeg/mpeg_points.h"

namespace roving {

// One direction: each point of `from` against `to`. Squared distances, in model units squared.
struct MpegDirection {
  std::size_t points = 0;
  double d1_mse = 0, d1_hausdorff = 0;
  double d2_mse = 0, d2_hausdorff = 0;           // where there is D2
  std::array<double, 3> ycbcr_mse{}, rgb_mse{};  // where there is colour
  std::array<double, 3> ycocg_mse{};             // YCoCg-R's, where asked for (PcErrorOptions::ycocg)
  std::array<double, 3> rgb_hausdorff{};         // largest squared difference per RGB channel
};

struct MpegFigures {
  double peak = 0;
  bool peak_given = false;  // from `resolution`, else the tool's default (MpegRules)
  bool d2 = false;          // A has normals
  bool colour = false;      // both have colour
  bool mmetric = false;     // by mmetric's rules (MpegRules)
  bool ycocg = false;       // YCoCg-R's colour figures too
  MpegDirection a_to_b, b_to_a;
  // The worse direction's figure (pc_error's "Final (symmetric)").
  MpegDirection symmetric() const;
};

// pc_error's options that change a figure, with its defaults (docs/mpeg.md's table). Under the
// defaults point_cloud_psnr's own search answers; under any other (and where A has NaN normals, which
// pc_error computes on with) pc_error's loop does, as it is written (pc_error_loop.h).
struct PcErrorOptions {
  // --dropdups: points at one position 0 all kept, 1 the first kept, 2 merged into one, colours
  // averaged. Applied as the clouds are read (mpeg_points.h).
  int dropdups = 2;
  // --neighborsProc: the colour of the points tied nearest: 0 the first the search finds, 1 their
  // mean (rounded), 2 their mean weighted by how many points each merged (with dropdups 2), 3 the
  // one nearest in RGB, 4 the one farthest in RGB.
  int neighbors_proc = 1;
  // --averageNormals: D2 averaged over the tied nearest points and A's normals carried onto all of
  // B's tied points; false: the first found alone, from a search of 10 points that does not grow.
  bool average_normals = true;
  bool ycocg = false;  // --mseSpace=8: YCoCg-R's colour figures too (RGB's and Y'CbCr's are always given)
  bool defaults() const { return dropdups == 2 && neighbors_proc == 1 && average_normals; }
};

// Where mmetric's `compare --mode pcc` (meshes sampled by mmetric_sampling.h) differs from pc_error.
struct MpegRules {
  std::optional<double> resolution;  // the peak; unset: the tool's default below
  bool mmetric = false;
  PcErrorOptions options;
  // mmetric's --normalCalcModificationEnable: A -> B's D2 along B's own normals where it has them.
  bool b_own_normals = true;
  // pc_error: ties are consecutive squared distances within 1e-8; mmetric passes 1e-20.
  double tie_threshold() const { return mmetric ? 1e-20 : 1e-8; }
  // mmetric: A -> B's D2 uses B's own normals where B has them (b_own_normals, its default
  // --normalCalcModificationEnable), and the default peak is the diagonal of A's box.
  bool b_normals_own() const { return mmetric && b_own_normals; }
};

// PSNR of a squared-distance figure with pc_error's geometry formula, 10 log10(3 p^2 / mse);
// +infinity where mse is 0.
double geometry_psnr(double mse, double peak);
// PSNR of a colour MSE against `peak` (1 for Y'CbCr on [0, 1], 255 for RGB); +infinity at 0.
double colour_psnr(double mse, double peak);

// Both directions' figures. Throws roving::Error for a resolution that is not finite and > 0, or,
// where none is given, for an A without extent (pc_error: no two points 1e-5 or more apart; no
// spacing to take as the peak), naming `a_name`.
MpegFigures mpeg_point_cloud_figures(const MpegPoints& a, const MpegPoints& b, const MpegRules& rules,
                                     const std::string& a_name);

}  // namespace roving
