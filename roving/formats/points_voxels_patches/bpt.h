// .bpt files: Bezier patches (the Utah teapot's format).
#pragma once

#include <string>

#include "roving/core/bezier_patches.h"

namespace roving {

// Reads a `.bpt` file: the patch count, then per patch "m n" and (m+1)(n+1) lines "x y z".
// Throws roving::Error naming the file and line for a bad count or degree (1..16), a missing or
// malformed control point, NaN/inf, or trailing garbage.
BezierSurface read_bpt(const std::string& path);

}  // namespace roving
