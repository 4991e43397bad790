// Icosphere, torus, square and exact sphere samples.
#include "analytic.h"

#include <cmath>
#include <map>

namespace roving {

TriangleMesh icosphere(const Vec3& centre, double radius, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& v : p) v.normalize();
  std::vector<Triangle> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = midpoint.try_emplace(key, static_cast<int>(p.size()));
      if (added) p.push_back((p[a] + p[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> next;
    for (const Triangle& tri : f) {
      const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]), ca = middle(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  for (Vec3& v : p) v = centre + radius * v;
  return TriangleMesh(std::move(p), std::move(f), "icosphere");
}

TriangleMesh torus(double major, double minor, int segments, int rings) {
  std::vector<Vec3> p;
  std::vector<Triangle> f;
  for (int i = 0; i < segments; ++i) {
    const double u = 2 * M_PI * i / segments;
    for (int j = 0; j < rings; ++j) {
      const double v = 2 * M_PI * j / rings;
      p.emplace_back((major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u),
                     minor * std::sin(v));
    }
  }
  const auto at = [&](int i, int j) { return (i % segments) * rings + (j % rings); };
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < rings; ++j) {
      f.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      f.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return TriangleMesh(std::move(p), std::move(f), "torus");
}

TriangleMesh square(double half, double height, int n) {
  std::vector<Vec3> p;
  std::vector<Triangle> f;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) p.emplace_back(-half + 2 * half * i / n, -half + 2 * half * j / n, height);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      f.push_back({a, b, d});
      f.push_back({a, d, c});
    }
  }
  return TriangleMesh(std::move(p), std::move(f), "square");
}

TriangleMesh smoothly_perturbed(const TriangleMesh& mesh, double amplitude, double wavelength) {
  std::vector<Vec3> moved = mesh.positions().to_vector();
  const double k = 2 * M_PI / wavelength;
  const std::vector<Vec3> normals = mesh.vertex_normals();
  for (std::size_t v = 0; v < moved.size(); ++v) {
    const Vec3& p = moved[v];
    const double wave = std::sin(k * p.x()) * std::cos(k * p.y() + 0.5) * std::sin(k * p.z() + 1.0);
    moved[v] += amplitude * wave * normals[v];
  }
  return TriangleMesh(std::move(moved), mesh.triangles(), "perturbed mesh");
}

PointCloud sphere_points(const Vec3& centre, double radius, std::size_t count) {
  PointCloud cloud;
  const double golden = M_PI * (3 - std::sqrt(5.0));
  for (std::size_t i = 0; i < count; ++i) {
    const double z = 1 - 2 * (i + 0.5) / count, r = std::sqrt(1 - z * z), phi = golden * i;
    const Vec3 n(r * std::cos(phi), r * std::sin(phi), z);
    cloud.positions.push_back(centre + radius * n);
    cloud.normals.push_back(n);
  }
  return cloud;
}

}  // namespace roving
