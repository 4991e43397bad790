#include "roving/mpeg/mmetric_sampling.h"

#include <fmt/format.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "roving/core/error.h"

namespace roving {
namespace {

struct Float3 {
  float x = 0, y = 0, z = 0;
  Float3 operator-(const Float3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Float3 operator*(float s) const { return {x * s, y * s, z * s}; }
  Float3 operator+(const Float3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  bool operator<(const Float3& o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
  bool operator==(const Float3& o) const { return x == o.x && y == o.y && z == o.z; }
};

Float3 cross(const Float3& a, const Float3& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}

float dot(const Float3& a, const Float3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// As glm: 0.5 * length(cross), the length in single precision.
double triangle_area(const Float3& a, const Float3& b, const Float3& c) {
  const Float3 n = cross(b - a, c - a);
  return 0.5 * double(std::sqrt(dot(n, n)));
}

// As glm::normalize: v * (1 / sqrt(v . v)).
Float3 triangle_normal(const Float3& a, const Float3& b, const Float3& c) {
  const Float3 n = cross(b - a, c - a);
  return n * (1.0f / std::sqrt(dot(n, n)));
}

// A sample: position, colour, normal; ordered as mmetric's vertex comparator orders them.
struct Vertex {
  Float3 position, colour, normal;
  bool operator<(const Vertex& o) const {
    return std::tie(position, colour, normal) < std::tie(o.position, o.colour, o.normal);
  }
};

// Keeps each distinct vertex once, in the order first pushed (mmetric's ModelBuilder).
class Builder {
 public:
  explicit Builder(bool colour, bool normals) : colour_(colour), normals_(normals) {}
  std::uint32_t push(const Vertex& v) {
    const auto [at, inserted] = index_.emplace(v, std::uint32_t(out_.positions.size()));
    if (!inserted) return at->second;
    out_.positions.emplace_back(v.position.x, v.position.y, v.position.z);
    if (normals_) out_.normals.emplace_back(v.normal.x, v.normal.y, v.normal.z);
    if (colour_) out_.colours.emplace_back(v.colour.x, v.colour.y, v.colour.z);
    return at->second;
  }
  PointCloud take() { return std::move(out_); }

 private:
  bool colour_, normals_;
  std::map<Vertex, std::uint32_t> index_;
  PointCloud out_;
};

// mmetric's recursive edge-midpoint subdivision, `depth` levels left.
void subdivide(const Vertex& a, const Vertex& b, const Vertex& c, int depth, Builder& out) {
  if (depth == 0 || triangle_area(a.position, b.position, c.position) < 2.0) return;
  const Float3 normal = triangle_normal(a.position, b.position, c.position);
  const auto middle = [&](const Vertex& p, const Vertex& q) {
    return Vertex{p.position * 0.5f + q.position * 0.5f, p.colour * 0.5f + q.colour * 0.5f, normal};
  };
  const Vertex ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
  out.push(ab);
  out.push(bc);
  out.push(ca);
  subdivide(ab, bc, ca, depth - 1, out);
  subdivide(a, ab, ca, depth - 1, out);
  subdivide(ab, b, bc, depth - 1, out);
  subdivide(bc, c, ca, depth - 1, out);
}

}  // namespace

PointCloud mmetric_samples(const TriangleMesh& mesh, const std::string& name) {
  if (mesh.texture_mapping()) {
    throw Error(fmt::format(
        "{}: a textured mesh; --pcc samples meshes as mmetric does with vertex colours or none (its "
        "texture fetch is not reproduced)",
        name));
  }
  const bool colour = !mesh.vertex_colours().empty();
  const auto corner = [&](std::size_t vertex) {
    const Vec3& p = mesh.positions()[vertex];
    Vertex v{{float(p.x()), float(p.y()), float(p.z())}, {}, {}};
    if (colour) {
      const Colour& c = mesh.vertex_colours()[vertex];
      v.colour = {c.x(), c.y(), c.z()};
    }
    return v;
  };
  // mmetric's "oriented" reordering: distinct vertices in sorted order, triangles rotated to start
  // at their smallest vertex, then sorted, repeated ones once.
  std::map<Vertex, std::uint32_t> sorted;
  for (const Triangle& t : mesh.triangles())
    for (const int i : t) sorted.emplace(corner(std::size_t(i)), 0);
  std::vector<Vertex> vertices;
  vertices.reserve(sorted.size());
  for (auto& [v, index] : sorted) {
    index = std::uint32_t(vertices.size());
    vertices.push_back(v);
  }
  std::set<std::array<std::uint32_t, 3>> triangles;
  for (const Triangle& t : mesh.triangles()) {
    std::array<std::uint32_t, 3> k;
    for (int c = 0; c < 3; ++c) k[c] = sorted.at(corner(std::size_t(t[c])));
    if (k[1] < k[0] && k[1] <= k[2]) {
      k = {k[1], k[2], k[0]};
    } else if (k[2] <= k[0] && k[2] < k[1]) {
      k = {k[2], k[0], k[1]};
    }
    triangles.insert(k);
  }

  Builder out(colour, true);
  for (const auto& t : triangles) {
    Vertex a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
    if (triangle_area(a.position, b.position, c.position) < DBL_EPSILON) continue;
    a.normal = b.normal = c.normal = triangle_normal(a.position, b.position, c.position);
    out.push(a);
    out.push(b);
    out.push(c);
    subdivide(a, b, c, 2, out);
  }
  return out.take();
}

}  // namespace roving
