// Exact CPU reference by Embree 3 ray casting; Embree's headers stay inside the .cpp.
#pragma once

#include <memory>
#include <string>

#include "roving/core/distance_method.h"

namespace roving {

// All three semantics: first-hit (rays in packets of 8) and nearest-on-line from one ray from x + h n along
// -n over [0, 2h] (nearest collects every crossing with a context filter and keeps the one closest to x), and
// closest point (Embree point queries). Robust traversal; a ray that still misses is re-cast from four
// origins offset by 1e-6 of the diagonal across it, and any triangle they hit is intersected with the
// original line: a line through a shared edge or vertex is not lost. Hit distances are recomputed in double
// against the hit triangle's plane. Multi-threaded with TBB.
std::unique_ptr<DistanceMethod> make_embree_reference();

// Embree's version, for reports.
std::string embree_version();

}  // namespace roving
