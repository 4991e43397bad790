// Exact reference distances on CGAL's AABB tree (DESIGN.md "Definitions"), and the accelerated
// vertex-to-plane baseline, which is its closest-point query.
#include "reference_cgal/cgal_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "roving/error.h"
#include "roving/geometry.h"
#include "roving/stopwatch.h"

namespace roving {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using TriangleList = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using SegmentHit = Tree::Intersection_and_primitive_id<Segment>::Type;

Point to_point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }
Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

class CgalAabbMethod final : public DistanceMethod {
 public:
  CgalAabbMethod(std::string name, std::vector<Semantics> semantics)
      : name_(std::move(name)), semantics_(std::move(semantics)) {}

  std::string name() const override { return name_; }
  std::vector<Semantics> supported_semantics() const override { return semantics_; }

  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    triangles_.clear();
    triangles_.reserve(test.triangle_count());
    const auto& p = test.positions();
    for (const Triangle& t : test.triangles()) {
      // CGAL's segment-triangle test asserts on degenerate triangles: they have no area to hit.
      Kernel::Triangle_3 triangle(to_point(p[t[0]]), to_point(p[t[1]]), to_point(p[t[2]]));
      if (!triangle.is_degenerate()) triangles_.push_back(triangle);
    }
    tree_.clear();
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
    if (supports(Semantics::Closest)) tree_.accelerate_distance_queries();
    built_ = true;
    return watch.seconds();
  }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!built_) throw Error(name_ + ": measure() called before build()");
    validate_options(*this, options);
    const Stopwatch watch;
    DistanceResult result;
    result.signed_distance.assign(samples.size(), 0.0);
    result.hit.assign(samples.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 128),
                      [&](const tbb::blocked_range<std::size_t>& range) {
      std::vector<SegmentHit> hits;
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const std::optional<double> d =
            options.semantics == Semantics::Closest
                ? std::optional<double>(closest(samples.positions[k], samples.normals[k]))
                : along_normal(samples.positions[k], samples.normals[k], options, hits);
        if (d) {
          result.hit[k] = 1;
          result.signed_distance[k] = *d;
        }
      }
    });
    result.query_seconds = watch.seconds();
    return result;
  }

 private:
  // Every crossing of the segment from x + h n (t = 0) to x - h n (t = 2h); d = h - t. First-hit
  // keeps the smallest t, nearest the smallest |d|. A segment lying in a triangle's plane meets
  // it in a segment: its end nearest the segment's start is the first point, and for nearest
  // the point of that overlap nearest to x.
  std::optional<double> along_normal(const Vec3& x, const Vec3& n, const DistanceOptions& options,
                                     std::vector<SegmentHit>& hits) const {
    const double h = options.max_error;
    const Vec3 start = x + h * n;
    hits.clear();
    tree_.all_intersections(Segment(to_point(start), to_point(x - h * n)), std::back_inserter(hits));
    std::optional<double> best;
    const auto consider = [&](double d) {
      d = std::clamp(d, -h, h);
      const bool better = !best || (options.semantics == Semantics::FirstHit
                                        ? d > *best
                                        : std::abs(d) < std::abs(*best));
      if (better) best = d;
    };
    for (const SegmentHit& hit : hits) {
      if (const Point* point = boost::get<Point>(&hit.first)) {
        consider((to_vec(*point) - x).dot(n));
      } else if (const Segment* overlap = boost::get<Segment>(&hit.first)) {
        const double d0 = (to_vec(overlap->source()) - x).dot(n);
        const double d1 = (to_vec(overlap->target()) - x).dot(n);
        if (options.semantics == Semantics::FirstHit) {
          consider(std::max(d0, d1));
        } else {
          consider(std::min(d0, d1) <= 0 && std::max(d0, d1) >= 0 ? 0.0
                   : std::abs(d0) < std::abs(d1)                  ? d0
                                                                  : d1);
        }
      }
    }
    return best;
  }

  double closest(const Vec3& x, const Vec3& n) const {
    return signed_offset(x, n, to_vec(tree_.closest_point(to_point(x))));
  }

  std::string name_;
  std::vector<Semantics> semantics_;
  TriangleList triangles_;
  Tree tree_;
  bool built_ = false;
};

}  // namespace

std::unique_ptr<DistanceMethod> make_cgal_reference() {
  return std::make_unique<CgalAabbMethod>(
      "cgal", std::vector<Semantics>{Semantics::FirstHit, Semantics::Nearest, Semantics::Closest});
}

std::unique_ptr<DistanceMethod> make_accelerated_vertex_to_plane() {
  return std::make_unique<CgalAabbMethod>("v2p-aabb", std::vector<Semantics>{Semantics::Closest});
}

}  // namespace roving
