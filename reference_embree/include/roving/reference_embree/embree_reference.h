// Exact CPU reference by Embree 3 ray casting; Embree's headers stay inside the .cpp.
#pragma once

#include <memory>
#include <string>

#include "roving/core/distance_method.h"
#include "roving/core/raw_queries.h"
#include "roving/core/sample_set.h"

namespace roving {

// All three semantics: first-hit and nearest on the line from one ray from x + h n along -n over
// [0, 2h], Embree's BVH finding the candidate triangles and the shared rule (normal_line.h)
// deciding each in double, so that it agrees with the CGAL reference bit for bit; closest point
// by Embree's point queries. Multi-threaded with TBB.
std::unique_ptr<DistanceMethod> make_embree_reference();

// Embree's own triangle BVH (robust) and queries on the same samples, without the shared rule:
// first-hit by rtcIntersect1 from x + h n along -n over 2h, nearest by one ray each way from x
// over h, closest by rtcPointQuery (roving/core/raw_queries.h).
RawRun raw_embree_queries(const TriangleMesh& test, const SampleSet& samples, Semantics semantics, double h);

// Embree's version, for reports.
std::string embree_version();

}  // namespace roving
