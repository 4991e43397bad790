// Exact CPU reference by Embree 3 ray casting; Embree's headers stay inside the .cpp.
#pragma once

#include <memory>

#include "roving/distance_method.h"

namespace roving {

// All three semantics: first-hit (one ray from x + h n along -n over [0, 2h]), nearest-on-line
// (one ray each way from just behind x) and closest point (Embree point queries).
// Robust traversal; a ray that still misses is re-cast from four origins offset by 1e-6 of the
// diagonal across the ray, and any triangle they hit is intersected exactly with the original
// ray's line: a ray through a shared edge or vertex cannot slip between its triangles.
// Multi-threaded with TBB.
std::unique_ptr<DistanceMethod> make_embree_reference();

}  // namespace roving
