// Colour spaces and the perceptual difference the colour report uses, on sRGB code values
// (roving::Colour, [0, 255]).
#pragma once

#include "roving/core/triangle_mesh.h"

namespace roving {

// sRGB's transfer function (IEC 61966-2-1): linear light on [0, 1] to a code value on [0, 255],
// and back.
double srgb_code(double linear);
double srgb_linear(double code);

// BT.709 Y'CbCr of gamma-encoded R'G'B' on the same scale, full range with no offsets (as MPEG's
// pc_error and mmetric convert): Y' = 0.2126 R' + 0.7152 G' + 0.0722 B', Cb = (B' - Y') / 1.8556,
// Cr = (R' - Y') / 1.5748. Differences, and so PSNR, do not depend on the offsets.
Vec3 ycbcr_bt709(const Vec3& rgb);

// CIELAB (D65 white, the sRGB primaries of IEC 61966-2-1) of an sRGB colour.
Vec3 srgb_to_lab(const Vec3& rgb);

// CIEDE2000 colour difference (kL = kC = kH = 1) of two CIELAB colours: Sharma, Wu and Dalal,
// "The CIEDE2000 color-difference formula", Color Research & Application 30(1), 2005.
double ciede2000(const Vec3& lab1, const Vec3& lab2);

}  // namespace roving
