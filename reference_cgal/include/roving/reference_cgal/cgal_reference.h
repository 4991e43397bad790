// Exact CPU reference on CGAL's AABB tree, and the paper's vertex-to-vertex and vertex-to-plane
// baselines. CGAL's headers stay inside the .cpp files.
#pragma once

#include <memory>
#include <string>

#include "roving/core/distance_method.h"
#include "roving/core/raw_queries.h"
#include "roving/core/sample_set.h"

namespace roving {

// All three semantics on an AABB tree of the test triangles, kernel Epick (exact predicates,
// inexact constructions): whether a segment meets a triangle is decided exactly, so a line
// through a shared edge or vertex is never lost; the hit point itself is computed in double.
// First-hit and nearest come from one query: every triangle the segment [x + h n, x - h n]
// meets (exact predicate), each crossing computed against the triangle's plane in double.
std::unique_ptr<DistanceMethod> make_cgal_reference();

// CGAL's own AABB tree and queries on the same samples, without the shared rule: first-hit by
// first_intersection of a ray from x + h n along -n (within 2h), nearest by one ray each way from
// x (within h), closest by closest_point (roving/core/raw_queries.h).
RawRun raw_cgal_queries(const TriangleMesh& test, const SampleSet& samples, Semantics semantics, double h);

enum class Search {
  Naive,        // brute force over every test element, as the paper timed it (multi-threaded)
  Accelerated,  // kd-tree over the vertices / AABB tree over the triangles
};

// Distance from each sample to the nearest vertex of M_C (referenced vertices only), signed by
// (c - x) . n. Semantics: closest (to vertices). Always a hit.
std::unique_ptr<DistanceMethod> make_vertex_to_vertex(Search search);

// Distance from each sample to the nearest point of M_C's triangles, signed by (c - x) . n.
// Semantics: closest. Always a hit.
std::unique_ptr<DistanceMethod> make_vertex_to_plane(Search search);

// CGAL's Polygon_mesh_processing::bounded_error_Hausdorff_distance from A to B (one-sided, within
// error_bound of the true value, parallel): the independent check of certified_hausdorff() and
// the speed it is compared with. Faces a CGAL Surface_mesh cannot hold are left out.
double cgal_bounded_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double error_bound);

// CGAL's version, for reports.
std::string cgal_version();

}  // namespace roving
