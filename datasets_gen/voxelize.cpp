// Conservative voxelisation by exact triangle-box overlap (CGAL's do_intersect(Triangle_3, Bbox_3)).
#include "voxelize.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "roving/core/error.h"

namespace roving {

namespace {

VoxelGrid voxelize(const TriangleMesh& mesh, int dimension, bool thin) {
  if (dimension < 1 || dimension > 1024) {
    throw Error(fmt::format("voxelize: expected a grid dimension in 1..1024, found {}", dimension));
  }
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  const BoundingBox& box = mesh.bounding_box();
  VoxelGrid grid;
  grid.dimension = dimension;
  grid.origin = box.min;
  grid.voxel_size = box.size().maxCoeff() / dimension;
  grid.occupied.assign(std::size_t(dimension) * dimension * dimension, 0);
  const auto cell = [&](double coordinate, int axis) {
    return std::clamp(static_cast<int>(std::floor((coordinate - grid.origin[axis]) / grid.voxel_size)), 0,
                      dimension - 1);
  };
  // Triangles in parallel; two writing the same voxel both write 1, so plain bytes are safe.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangle_count(), 256), [&](const auto& range) {
    for (std::size_t f = range.begin(); f != range.end(); ++f) {
      const Triangle& t = mesh.triangles()[f];
      const auto& p = mesh.positions();
      const Kernel::Triangle_3 triangle({p[t[0]].x(), p[t[0]].y(), p[t[0]].z()},
                                        {p[t[1]].x(), p[t[1]].y(), p[t[1]].z()},
                                        {p[t[2]].x(), p[t[2]].y(), p[t[2]].z()});
      if (triangle.is_degenerate()) continue;
      int low[3], high[3];
      for (int axis = 0; axis < 3; ++axis) {
        // One voxel of slack each way: a triangle on a voxel boundary touches both cubes.
        low[axis] = std::max(0, cell(std::min({p[t[0]][axis], p[t[1]][axis], p[t[2]][axis]}), axis) - 1);
        high[axis] =
            std::min(dimension - 1, cell(std::max({p[t[0]][axis], p[t[1]][axis], p[t[2]][axis]}), axis) + 1);
      }
      for (int x = low[0]; x <= high[0]; ++x)
        for (int y = low[1]; y <= high[1]; ++y)
          for (int z = low[2]; z <= high[2]; ++z) {
            const Vec3 a = grid.origin + grid.voxel_size * Vec3(x, y, z);
            const Vec3 b = a + Vec3::Constant(grid.voxel_size);
            if (thin) {
              const Vec3 n = mesh.face_normal(f);
              const Vec3 centre = a + Vec3::Constant(0.5 * grid.voxel_size);
              if (std::abs(n.dot(centre - p[t[0]])) > 0.5 * grid.voxel_size * n.cwiseAbs().maxCoeff())
                continue;
            }
            if (CGAL::do_intersect(triangle, CGAL::Bbox_3(a.x(), a.y(), a.z(), b.x(), b.y(), b.z()))) {
              grid.occupied[grid.index(x, y, z)] = 1;
            }
          }
    }
  });
  return grid;
}

}  // namespace

VoxelGrid voxelize_conservative(const TriangleMesh& mesh, int dimension) {
  return voxelize(mesh, dimension, false);
}
VoxelGrid voxelize_thin(const TriangleMesh& mesh, int dimension) {
  return voxelize(mesh, dimension, true);
}

}  // namespace roving
