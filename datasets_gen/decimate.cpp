// Quadric-error decimation to an exact triangle count with OpenMesh's DecimaterT + ModQuadricT.
#include "decimate.h"

#include <fmt/format.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <limits>

#include "roving/core/error.h"

namespace roving {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

}  // namespace

TriangleMesh decimate_quadric(const TriangleMesh& input, std::size_t target_triangles) {
  Mesh mesh;
  std::vector<Mesh::VertexHandle> handles;
  for (const Vec3& p : input.positions()) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  for (const Triangle& t : input.triangles()) {
    if (!mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid()) {
      throw Error("decimate: the mesh is not manifold; OpenMesh's decimater needs a manifold mesh");
    }
  }
  mesh.update_face_normals();

  OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  decimater.add(quadric);
  decimater.initialize();
  decimater.decimate_to_faces(0, target_triangles + 1);
  mesh.garbage_collection();  // n_faces() counts deleted faces until then
  if (mesh.n_faces() == target_triangles + 1) {
    // One triangle too many: collapse the shortest boundary edge that can go, which removes
    // exactly one face.
    Mesh::HalfedgeHandle best;
    double best_length = std::numeric_limits<double>::infinity();
    for (const auto h : mesh.halfedges()) {
      if (!mesh.is_boundary(mesh.opposite_halfedge_handle(h))) continue;
      const double length =
          (mesh.point(mesh.to_vertex_handle(h)) - mesh.point(mesh.from_vertex_handle(h))).norm();
      if (length < best_length && mesh.is_collapse_ok(h)) best = h, best_length = length;
    }
    if (best.is_valid()) mesh.collapse(best);
  }
  mesh.garbage_collection();
  if (mesh.n_faces() != target_triangles) {
    throw Error(fmt::format("decimate: reached {} triangles, not the {} asked for", mesh.n_faces(),
                            target_triangles));
  }

  std::vector<Vec3> positions;
  std::vector<int> index(mesh.n_vertices(), -1);
  for (const auto v : mesh.vertices()) {
    if (mesh.valence(v) == 0) continue;  // isolated: drop
    index[v.idx()] = static_cast<int>(positions.size());
    const auto& p = mesh.point(v);
    positions.emplace_back(p[0], p[1], p[2]);
  }
  std::vector<Triangle> triangles;
  for (const auto f : mesh.faces()) {
    Triangle t{};
    int corner = 0;
    for (const auto v : mesh.fv_range(f)) t[corner++] = index[v.idx()];
    triangles.push_back(t);
  }
  return TriangleMesh(std::move(positions), std::move(triangles), "decimated mesh");
}

}  // namespace roving
