// Where each sample's answer lies on TEST: the point its distance was measured to, and that
// point's barycentric coordinates in the face it lies on, for users who need more than d (a
// per-sample correspondence, as --samples-out and Python's per_sample give it).
#pragma once

#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/sample_set.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

struct Correspondences {
  // The point on TEST: where the normal line meets it (x + d n) or, under closest semantics, the
  // closest point; NaN for a no-hit and for a closest answer whose face is unknown.
  std::vector<Vec3> points;
  // Its weights of result.hit_face's three corners (non-negative, summing to 1); NaN where the
  // method does not name the face (the GL methods, the nearest-vertex baseline) or for a no-hit.
  std::vector<Vec3> barycentric;
};

// The correspondence of every sample by the colour rule (colour.h): with a face known, the point of
// that face nearest correspondence_point(x, n, d), which is the closest point itself under closest
// semantics and the normal line's crossing otherwise (within the line rule's widening of the
// triangles, 1e-6 of TEST's diagonal: normal_line.h). `test` is the mesh the distances were
// measured against.
Correspondences correspondences(const SampleSet& samples, const TriangleMesh& test, const DistanceResult& result,
                                Semantics semantics);

}  // namespace roving
