// Vertex-to-plane baseline (the paper's Table 3): distance to the nearest point of M_C's
// triangles. The naive form tests every triangle, as the paper timed it.
#include "closest_point_baseline.h"
#include "roving/reference_cgal/cgal_reference.h"

namespace roving {
namespace {

class NaiveVertexToPlane final : public ClosestPointBaseline {
 public:
  std::string name() const override { return "v2p-naive"; }
  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    corners_.clear();
    corners_.reserve(test.triangle_count());
    const auto& p = test.positions();
    for (const Triangle& t : test.triangles()) corners_.push_back({p[t[0]], p[t[1]], p[t[2]]});
    test_ = &test;
    built_ = true;
    return watch.seconds();
  }

 protected:
  bool nearest_is_a_vertex() const override { return false; }
  Nearest nearest(const Vec3& x) const override {
    double best = std::numeric_limits<double>::infinity();
    Nearest found{x, 0};
    for (std::size_t f = 0; f < corners_.size(); ++f) {
      const auto& [a, b, c] = corners_[f];
      const Vec3 candidate = closest_point_on_triangle(x, a, b, c);
      const double d = (candidate - x).squaredNorm();
      if (d < best) best = d, found = {candidate, static_cast<std::uint32_t>(f)};
    }
    return found;
  }

 private:
  std::vector<std::array<Vec3, 3>> corners_;
};

}  // namespace

std::unique_ptr<DistanceMethod> make_vertex_to_plane(Search search) {
  if (search == Search::Naive) return std::make_unique<NaiveVertexToPlane>();
  return make_accelerated_vertex_to_plane();
}

}  // namespace roving
