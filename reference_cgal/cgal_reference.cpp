// Exact reference distances on CGAL's AABB tree (DESIGN.md "Definitions"), and the accelerated
// vertex-to-plane baseline, which is its closest-point query.
#include "roving/reference_cgal/cgal_reference.h"

#include <CGAL/version.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "aabb_tree.h"
#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/normal_line.h"
#include "roving/core/stopwatch.h"

namespace roving {
namespace {

using namespace aabb;
using Segment = Kernel::Segment_3;

// Traversal that lists every triangle a segment meets. CGAL's own listing tests boxes with
// interval arithmetic, which was most of the query time; here boxes are tested in plain double
// after inflating them by `margin`, far above the slab test's rounding, so a box can only be
// let in wrongly, never kept out. The triangle test stays Epick's exact predicate.
class CrossedTriangles {
 public:
  CrossedTriangles(const Segment& segment, double margin, std::vector<Primitive::Id>& crossed)
      : start_(to_vec(segment.source())),
        delta_(to_vec(segment.target()) - start_),
        margin_(margin),
        crossed_(crossed) {}

  bool go_further() const { return true; }

  void intersection(const Segment&, const Primitive& primitive) { crossed_.push_back(primitive.id()); }

  template <class Node>
  bool do_intersect(const Segment&, const Node& node) const {
    const CGAL::Bbox_3& box = node.bbox();
    double enter = 0, leave = 1;  // segment parameter range inside the slabs so far
    for (int axis = 0; axis < 3; ++axis) {
      const double low = box.min(axis) - margin_, high = box.max(axis) + margin_;
      if (delta_[axis] == 0) {
        if (start_[axis] < low || start_[axis] > high) return false;
        continue;
      }
      double t0 = (low - start_[axis]) / delta_[axis], t1 = (high - start_[axis]) / delta_[axis];
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      leave = std::min(leave, t1);
      if (enter > leave) return false;
    }
    return true;
  }

 private:
  Vec3 start_, delta_;
  double margin_;
  std::vector<Primitive::Id>& crossed_;
};

class CgalAabbMethod final : public DistanceMethod {
 public:
  CgalAabbMethod(std::string name, std::vector<Semantics> semantics)
      : name_(std::move(name)), semantics_(std::move(semantics)) {}

  std::string name() const override { return name_; }
  std::vector<Semantics> supported_semantics() const override { return semantics_; }

  double build(const TriangleMesh& test) override {
    const Stopwatch watch;
    // Every triangle, degenerate ones too: under the shared rule a zero-area triangle is a
    // segment or a point, met by a line passing within the tolerance.
    triangles_ = triangles_of(test);
    test_ = &test;
    tolerance_ = kNormalLineTolerance * test.bounding_box().diagonal();
    tree_.clear();
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
    // 1e-9 of the model's extent: ~1e7 ulps of the coordinates, so the double slab test errs
    // only on the side of letting a box in.
    box_margin_ = 1e-9 * (test.bounding_box().diagonal() + test.bounding_box().max.cwiseAbs().maxCoeff() +
                          test.bounding_box().min.cwiseAbs().maxCoeff());
    distance_accelerated_ = false;
    built_ = true;
    return watch.seconds();
  }

  void release() override {
    tree_.clear();
    TriangleList().swap(triangles_);
    built_ = false;
  }

  DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) override {
    if (!built_) throw Error(name_ + ": measure() called before build()");
    validate_options(*this, options);
    // Closest-point queries need CGAL's search tree of the triangles' points, the others never
    // read it: made by the first closest-point measure, not by every build.
    if (options.semantics == Semantics::Closest && !distance_accelerated_) {
      tree_.accelerate_distance_queries();
      distance_accelerated_ = true;
    }
    return measure_each(
        samples.size(),
        [&](std::size_t k) {
          const Vec3& x = samples.positions[k];
          const Vec3& n = samples.normals[k];
          return options.semantics == Semantics::Closest ? std::optional<FaceHit>(closest(x, n))
                                                         : along_normal(x, n, options);
        },
        progress_, options.colour || options.faces);
  }

 private:
  // The crossings of the normal line by the shared rule (roving/core/normal_line.h): the tree
  // lists the triangles whose boxes, widened by the rule's tolerance, the segment from
  // x + h n to x - h n meets; NormalLine decides each, exactly as the Embree reference does.
  std::optional<FaceHit> along_normal(const Vec3& x, const Vec3& n, const DistanceOptions& options) const {
    const double h = options.max_error;
    const Segment segment(to_point(x + h * n), to_point(x - h * n));
    thread_local std::vector<Primitive::Id> crossed;  // scratch, reused across queries
    crossed.clear();
    CrossedTriangles traversal(segment, box_margin_ + tolerance_, crossed);
    tree_.traversal(segment, traversal);
    const NormalLine line(x, n, h, tolerance_);
    CrossingChoice choice(options.semantics, h);
    const auto& p = test_->positions();
    for (const Primitive::Id& id : crossed) {
      const Triangle& t = test_->triangles()[id - triangles_.begin()];
      const auto face = static_cast<std::uint32_t>(id - triangles_.begin());
      if (choice.settled_for(face)) continue;
      if (const auto crossing = line.crossing(p[t[0]], p[t[1]], p[t[2]])) choice.consider(*crossing, face);
    }
    return choice.chosen_hit();
  }

  // CGAL's closest point and its face; among equally near faces CGAL keeps the first it visits
  // (the same point wherever they meet at an edge or a vertex).
  FaceHit closest(const Vec3& x, const Vec3& n) const {
    const auto [point, id] = tree_.closest_point_and_primitive(to_point(x));
    return {signed_offset(x, n, to_vec(point)), static_cast<std::uint32_t>(id - triangles_.begin())};
  }

  std::string name_;
  std::vector<Semantics> semantics_;
  TriangleList triangles_;  // in the test mesh's order: a primitive's offset is its face
  const TriangleMesh* test_ = nullptr;
  double tolerance_ = 0;
  Tree tree_;
  double box_margin_ = 0;
  bool built_ = false, distance_accelerated_ = false;
};

}  // namespace

std::string cgal_version() {
  return CGAL_VERSION_STR;
}

std::unique_ptr<DistanceMethod> make_cgal_reference() {
  return std::make_unique<CgalAabbMethod>(
      "cgal", std::vector<Semantics>{Semantics::FirstHit, Semantics::Nearest, Semantics::Closest});
}

std::unique_ptr<DistanceMethod> make_accelerated_vertex_to_plane() {
  return std::make_unique<CgalAabbMethod>("v2p-aabb", std::vector<Semantics>{Semantics::Closest});
}

}  // namespace roving
