// Vertex-to-vertex baseline (the paper's Table 3): distance to the nearest vertex of M_C.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>

#include <array>
#include <map>

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
    indices_.clear();
    for (std::size_t v = 0; v < test.vertex_count(); ++v) {
      if (!test.vertex_referenced()[v]) continue;
      vertices_.push_back(test.positions()[v]);
      indices_.push_back(static_cast<std::uint32_t>(v));
    }
    test_ = &test;
    built_ = true;
    return watch.seconds();
  }

 protected:
  bool nearest_is_a_vertex() const override { return true; }
  Nearest nearest(const Vec3& x) const override {
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_index = 0;
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
      const double d = (vertices_[i] - x).squaredNorm();
      if (d < best) best = d, best_index = i;
    }
    return {vertices_[best_index], indices_[best_index]};
  }

 private:
  std::vector<Vec3> vertices_;
  std::vector<std::uint32_t> indices_;  // each of vertices_' index in TEST
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
    index_of_.clear();  // made when colour asks for it
    for (std::size_t v = 0; v < test.vertex_count(); ++v) {
      if (!test.vertex_referenced()[v]) continue;
      const Vec3& p = test.positions()[v];
      tree_->insert(Kernel::Point_3(p.x(), p.y(), p.z()));
    }
    tree_->build();  // queries from several threads need the tree built up front
    test_ = &test;
    built_ = true;
    return watch.seconds();
  }
  void release() override {
    tree_.reset();
    index_of_.clear();
    built_ = false;
  }

 protected:
  bool nearest_is_a_vertex() const override { return true; }
  void index_vertices() override {
    if (!index_of_.empty()) return;
    for (std::size_t v = 0; v < test_->vertex_count(); ++v) {
      const Vec3& p = test_->positions()[v];
      if (test_->vertex_referenced()[v]) index_of_.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(v));
    }  // try_emplace: the lowest index of equal positions
  }
  // Its index is known only after index_vertices(); 0 before.
  Nearest nearest(const Vec3& x) const override {
    const NeighborSearch search(*tree_, Kernel::Point_3(x.x(), x.y(), x.z()), 1);
    // A copy: the search iterator hands out its pair by value, so a reference would dangle.
    const Kernel::Point_3 p = search.begin()->first;
    const auto it = index_of_.find({p.x(), p.y(), p.z()});
    return {Vec3(p.x(), p.y(), p.z()), it == index_of_.end() ? 0u : it->second};
  }

 private:
  std::unique_ptr<NeighborSearch::Tree> tree_;
  std::map<std::array<double, 3>, std::uint32_t> index_of_;  // a vertex's position to its index in TEST
};

}  // namespace

std::unique_ptr<DistanceMethod> make_vertex_to_vertex(Search search) {
  if (search == Search::Naive) return std::make_unique<NaiveVertexToVertex>();
  return std::make_unique<KdTreeVertexToVertex>();
}

}  // namespace roving
