// Analytic test shapes whose distances are known in closed form.
#pragma once

#include "roving/core/triangle_mesh.h"
#include "roving/formats/points_voxels_patches/point_cloud_io.h"

namespace roving {

// Icosphere of `radius` about `centre`: the icosahedron subdivided `levels` times, every vertex
// projected onto the sphere (so the mesh lies inside the sphere, touching it at its vertices).
TriangleMesh icosphere(const Vec3& centre, double radius, int levels);

// Torus about the z axis: tube radius `minor` around the circle of radius `major`,
// `segments` x `rings` quads split into triangles, vertices on the exact torus.
TriangleMesh torus(double major, double minor, int segments, int rings);

// The square [-half, half]^2 in the plane z = height, n x n quads, normal +z.
TriangleMesh square(double half, double height, int n);

// `mesh` with every vertex moved along its normal by `amplitude` times a smooth wave
// sin(k x) cos(k y + 0.5) sin(k z + 1), k = 2 pi / `wavelength`: a test model close to the
// reference everywhere, for the accuracy gates.
TriangleMesh smoothly_perturbed(const TriangleMesh& mesh, double amplitude, double wavelength);

// `count` points of the exact sphere with their exact outward normals (Fibonacci lattice:
// deterministic, near-uniform by area).
PointCloud sphere_points(const Vec3& centre, double radius, std::size_t count);

}  // namespace roving
