// The one-sided Hausdorff distance between two triangle surfaces, certified: an interval that
// contains the true value, as narrow as asked. Embree's headers stay inside the .cpp.
#pragma once

#include <cstddef>
#include <memory>

#include "roving/core/distance_method.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

struct HausdorffInterval {
  double lower = 0;  // a distance attained: |lower_point - lower_closest|
  double upper = 0;  // no point of A is farther than this from B
  Vec3 lower_point = Vec3::Zero();    // the point of A found farthest from B
  Vec3 lower_closest = Vec3::Zero();  // its closest point on B
  std::size_t distance_queries = 0;   // closest-point queries on B made
  std::size_t triangles_split = 0;    // subdivisions of A's triangles the bound needed
  double seconds = 0;
};

// h(A, B) = max over points a of A's triangles of the distance from a to B's triangles, bracketed
// as lower <= h(A, B) <= upper with upper - lower <= max_gap (> 0). Branch and bound over A's
// triangles: a triangle's lower bound is the largest distance at its vertices (points of A); its
// upper bound is, for each candidate triangle T of B (the closest ones of its vertices and its
// parent's), the largest distance from its vertices to T, the smallest over T: the distance to one
// triangle is convex, so over a triangle of A it peaks at a vertex, and the distance to B is at
// most that. The triangle with the largest upper bound is split in four until every upper bound is
// within max_gap of the best lower bound. Closest points by Embree's BVH (boxes padded against its
// float rounding), distances in double; both cores (TBB). `progress` hears ("vertices", done,
// total) as A's vertices are measured, then ("pieces", split, split + left) as the pieces above the
// gap are split (what it throws stops the work and is rethrown: Ctrl-C's way in). Throws
// roving::Error on an empty mesh.
HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap,
                                      const ProgressFn& progress = {});

// The same over A's triangles [first, last) alone (a shard's share): the largest lower and upper
// ends over shards covering A make an interval of the whole A with the same guarantee and width,
// though its ends may differ from the whole run's within that width (the best lower bound a
// shard prunes with is its own).
HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap,
                                      std::size_t first, std::size_t last, const ProgressFn& progress = {});

class ClosestPoints;

// A given a part at a time against one B (a reference read a block of faces at a time): B's search
// structure is built once and each part bounded as a shard's share is, pruning with the largest
// lower bound of the parts before it. After the last part, interval() holds h(A, B) within max_gap
// as the shards' merged interval does (its ends may differ from one whole run's within that width).
// One part that is all of A gives certified_hausdorff's interval exactly.
class CertifiedHausdorff {
 public:
  // Throws roving::Error on an empty B or a gap that is not positive and finite.
  CertifiedHausdorff(const TriangleMesh& b, double max_gap);
  ~CertifiedHausdorff();
  CertifiedHausdorff(const CertifiedHausdorff&) = delete;
  CertifiedHausdorff& operator=(const CertifiedHausdorff&) = delete;

  // A's triangles [first, last); throws roving::Error on an empty A or a range outside it.
  void add(const TriangleMesh& a, std::size_t first, std::size_t last, const ProgressFn& progress = {});
  void add(const TriangleMesh& a) { add(a, 0, a.triangle_count()); }
  // The interval over the parts added, each end widened by the closest-point kernel's error bound
  // (roving/core/geometry.h), so that it holds the exact value; throws roving::Error where none was.
  HausdorffInterval interval() const;

 private:
  std::unique_ptr<ClosestPoints> closest_;
  double max_gap_ = 0;
  bool added_ = false, attained_ = false;  // attained_: the lower end has a point of A
  double largest_coordinate_ = 0;            // of A and B: the scale of the distances' rounding
  HausdorffInterval result_;
};

}  // namespace roving
