// Vertex-to-vertex baseline (the paper's Table 3): distance to the nearest vertex of M_C.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>

#include "closest_point_baseline.h"
#include "roving/reference_cgal/cgal_reference.h"

namespace roving {
namespace {

class NaiveVertexToVertex final : public ClosestPointBaseline {
 public:
  std::string name() const override { return "v2v-naive"; }
  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    vertices_.clear();
    for (std::size_t v = 0; v < test.vertex_count(); ++v) {
      if (test.vertex_referenced()[v]) vertices_.push_back(test.positions()[v]);
    }
    built_ = true;
    return watch.seconds();
  }

 protected:
  Vec3 nearest(const Vec3& x) const override {
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_index = 0;
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
      const double d = (vertices_[i] - x).squaredNorm();
      if (d < best) best = d, best_index = i;
    }
    return vertices_[best_index];
  }

 private:
  std::vector<Vec3> vertices_;
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SearchTraits = CGAL::Search_traits_3<Kernel>;
using NeighborSearch = CGAL::Orthogonal_k_neighbor_search<SearchTraits>;

class KdTreeVertexToVertex final : public ClosestPointBaseline {
 public:
  std::string name() const override { return "v2v-kdtree"; }
  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    tree_ = std::make_unique<NeighborSearch::Tree>();
    for (std::size_t v = 0; v < test.vertex_count(); ++v) {
      if (!test.vertex_referenced()[v]) continue;
      const Vec3& p = test.positions()[v];
      tree_->insert(Kernel::Point_3(p.x(), p.y(), p.z()));
    }
    tree_->build();  // queries from several threads need the tree built up front
    built_ = true;
    return watch.seconds();
  }
  void release() override {
    tree_.reset();
    built_ = false;
  }

 protected:
  Vec3 nearest(const Vec3& x) const override {
    const NeighborSearch search(*tree_, Kernel::Point_3(x.x(), x.y(), x.z()), 1);
    // A copy: the search iterator hands out its pair by value, so a reference would dangle.
    const Kernel::Point_3 p = search.begin()->first;
    return Vec3(p.x(), p.y(), p.z());
  }

 private:
  std::unique_ptr<NeighborSearch::Tree> tree_;
};

}  // namespace

std::unique_ptr<DistanceMethod> make_vertex_to_vertex(Search search) {
  if (search == Search::Naive) return std::make_unique<NaiveVertexToVertex>();
  return std::make_unique<KdTreeVertexToVertex>();
}

}  // namespace roving
