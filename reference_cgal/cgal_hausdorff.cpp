// CGAL's bounded-error Hausdorff distance (Polygon_mesh_processing, CGAL 5.4 and later), the
// independent check and the speed comparison for our certified interval.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>

#include "roving/core/error.h"
#include "roving/reference_cgal/cgal_reference.h"

namespace roving {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

SurfaceMesh surface_mesh(const TriangleMesh& mesh) {
  SurfaceMesh out;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(mesh.vertex_count());
  for (const Vec3& p : mesh.positions()) vertices.push_back(out.add_vertex({p.x(), p.y(), p.z()}));
  for (const Triangle& t : mesh.triangles()) {
    // A face Surface_mesh cannot hold (degenerate, or a non-manifold edge) is left out: CGAL's
    // function needs a valid halfedge structure. Such faces change h only where they stand alone.
    out.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  }
  return out;
}

}  // namespace

double cgal_bounded_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double error_bound) {
  if (a.triangle_count() == 0 || b.triangle_count() == 0) throw Error("cgal Hausdorff: an empty mesh");
  const SurfaceMesh ma = surface_mesh(a), mb = surface_mesh(b);
  return CGAL::Polygon_mesh_processing::bounded_error_Hausdorff_distance<CGAL::Parallel_if_available_tag>(
      ma, mb, error_bound);
}

}  // namespace roving
