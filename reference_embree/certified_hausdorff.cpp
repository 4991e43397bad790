// Certified one-sided Hausdorff distance by branch and bound over A's triangles (see the header).
#include "roving/reference_embree/certified_hausdorff.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>

#include "roving/core/error.h"
#include "roving/core/geometry.h"
#include "roving/core/stopwatch.h"
#include "embree_queries.h"

namespace roving {
namespace {

// Closest points on a triangle mesh by Embree's BVH over its triangles' boxes.
class ClosestPoints {
 public:
  explicit ClosestPoints(const TriangleMesh& mesh) : mesh_(mesh) {
    origin_ = mesh.bounding_box().centre();
    pad_ = 1e-6 * mesh.bounding_box().diagonal() + 1e-30;
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(mesh.triangle_count()));
    rtcSetGeometryUserData(geometry, this);
    rtcSetGeometryBoundsFunction(geometry, bounds, this);
    rtcSetGeometryPointQueryFunction(geometry, visit);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw Error("embree: building the BVH for closest points failed");
  }
  ~ClosestPoints() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  ClosestPoints(const ClosestPoints&) = delete;
  ClosestPoints& operator=(const ClosestPoints&) = delete;

  struct Found {
    double distance = std::numeric_limits<double>::infinity();
    Vec3 point = Vec3::Zero();
    std::uint32_t triangle = 0;
  };

  Found query(const Vec3& x) const {
    State state{this, x, {}};
    RTCPointQuery query = point_query(x - origin_, std::numeric_limits<float>::infinity());
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, nullptr, &state);
    return state.found;
  }

  // The distance from x to triangle `t` of the mesh, in double.
  double distance_to(const Vec3& x, std::uint32_t t) const {
    const Triangle& tri = mesh_.triangles()[t];
    const auto& p = mesh_.positions();
    return (closest_point_on_triangle(x, p[tri[0]], p[tri[1]], p[tri[2]]) - x).norm();
  }

 private:
  struct State {
    const ClosestPoints* self;
    Vec3 query;
    Found found;
  };

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const ClosestPoints*>(args->geometryUserPtr);
    const Triangle& t = self->mesh_.triangles()[args->primID];
    const auto& p = self->mesh_.positions();
    const Vec3 low = p[t[0]].cwiseMin(p[t[1]]).cwiseMin(p[t[2]]) - self->origin_ - Vec3::Constant(self->pad_);
    const Vec3 high = p[t[0]].cwiseMax(p[t[1]]).cwiseMax(p[t[2]]) - self->origin_ + Vec3::Constant(self->pad_);
    write_bounds(low, high, args->bounds_o);
  }

  static bool visit(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<State*>(args->userPtr);
    const double distance = state->self->distance_to(state->query, args->primID);
    if (distance >= state->found.distance) return false;
    const Triangle& t = state->self->mesh_.triangles()[args->primID];
    const auto& p = state->self->mesh_.positions();
    state->found = {distance, closest_point_on_triangle(state->query, p[t[0]], p[t[1]], p[t[2]]), args->primID};
    // Shrink the search sphere, padded so that float rounding never culls the true closest.
    args->query->radius = static_cast<float>(distance * (1 + 1e-6) + state->self->pad_);
    return true;
  }

  const TriangleMesh& mesh_;
  Vec3 origin_;
  double pad_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// A piece of one of A's triangles, with its corners' distances to B and the candidate triangles of
// B its upper bound was taken over.
struct Piece {
  std::array<Vec3, 3> corner;
  std::array<double, 3> distance;
  std::array<std::uint32_t, 6> candidates;
  int candidate_count = 0;
  double upper = 0;
  bool operator<(const Piece& other) const { return upper < other.upper; }  // a max-heap by upper bound
};

// The upper bound over the piece's candidates (see the header).
void bound(Piece& piece, const ClosestPoints& b) {
  piece.upper = std::numeric_limits<double>::infinity();
  for (int c = 0; c < piece.candidate_count; ++c) {
    double worst = 0;
    for (const Vec3& x : piece.corner) worst = std::max(worst, b.distance_to(x, piece.candidates[c]));
    piece.upper = std::min(piece.upper, worst);
  }
}

// The candidates of a piece: its corners' closest triangles, then its parent's, without repeats.
void add_candidate(Piece& piece, std::uint32_t t) {
  for (int c = 0; c < piece.candidate_count; ++c) {
    if (piece.candidates[c] == t) return;
  }
  if (piece.candidate_count < static_cast<int>(piece.candidates.size())) piece.candidates[piece.candidate_count++] = t;
}

}  // namespace

HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap) {
  return certified_hausdorff(a, b, max_gap, 0, a.triangle_count());
}

HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap,
                                      std::size_t first, std::size_t last) {
  if (a.triangle_count() == 0 || b.triangle_count() == 0) {
    throw Error("certified Hausdorff distance: expected two meshes with triangles, found an empty one");
  }
  if (!(max_gap > 0) || !std::isfinite(max_gap)) {
    throw Error(fmt::format("--hausdorff-bound: expected a positive finite gap, found {}", max_gap));
  }
  if (first > last || last > a.triangle_count()) {
    throw Error(fmt::format("certified Hausdorff distance: triangles [{}, {}) are not within A's {}", first, last,
                            a.triangle_count()));
  }
  const Stopwatch watch;
  HausdorffInterval result;
  const ClosestPoints closest(b);

  // Every vertex of A's triangles: its distance to B (a lower bound), its closest triangle (a candidate).
  const auto& positions = a.positions();
  const auto& triangles = a.triangles();
  std::vector<bool> used = a.vertex_referenced();
  const bool whole = first == 0 && last == a.triangle_count();
  if (!whole) {
    used.assign(positions.size(), false);
    for (std::size_t t = first; t < last; ++t) {
      for (const int v : triangles[t]) used[v] = true;
    }
  }
  std::vector<ClosestPoints::Found> at_vertex(positions.size());
  tbb::parallel_for(std::size_t{0}, positions.size(), [&](std::size_t v) {
    if (used[v]) at_vertex[v] = closest.query(positions[v]);
  });
  result.distance_queries = whole ? positions.size() : static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  const auto raise_lower = [&](const Vec3& x, const ClosestPoints::Found& f) {
    if (f.distance > result.lower) result.lower = f.distance, result.lower_point = x, result.lower_closest = f.point;
  };
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (used[v]) raise_lower(positions[v], at_vertex[v]);
  }

  std::vector<Piece> heap;
  double settled = 0;  // the largest upper bound of the pieces set aside (within the gap)
  const auto keep = [&](Piece&& piece) {
    if (piece.upper <= result.lower + max_gap) {
      settled = std::max(settled, piece.upper);
    } else {
      heap.push_back(std::move(piece));
      std::push_heap(heap.begin(), heap.end());
    }
  };
  for (std::size_t k = first; k < last; ++k) {
    const Triangle& t = triangles[k];
    Piece piece;
    for (int i = 0; i < 3; ++i) {
      piece.corner[i] = positions[t[i]];
      piece.distance[i] = at_vertex[t[i]].distance;
      add_candidate(piece, at_vertex[t[i]].triangle);
    }
    bound(piece, closest);
    keep(std::move(piece));
  }

  // Split the pieces with the largest upper bounds, a batch at a time on every core.
  while (!heap.empty() && heap.front().upper > result.lower + max_gap) {
    std::vector<Piece> batch;
    while (!heap.empty() && batch.size() < 4096 && heap.front().upper > result.lower + max_gap) {
      std::pop_heap(heap.begin(), heap.end());
      batch.push_back(std::move(heap.back()));
      heap.pop_back();
    }
    std::vector<std::array<Piece, 4>> children(batch.size());
    std::vector<std::array<std::pair<Vec3, ClosestPoints::Found>, 3>> midpoints(batch.size());
    tbb::parallel_for(std::size_t{0}, batch.size(), [&](std::size_t k) {
      const Piece& parent = batch[k];
      std::array<Vec3, 3> m;
      std::array<ClosestPoints::Found, 3> f;
      for (int i = 0; i < 3; ++i) {
        m[i] = 0.5 * (parent.corner[i] + parent.corner[(i + 1) % 3]);
        f[i] = closest.query(m[i]);
        midpoints[k][i] = {m[i], f[i]};
      }
      // Corners 0, 1, 2 and midpoints m0 (0-1), m1 (1-2), m2 (2-0): four children.
      const std::array<std::array<int, 3>, 4> shape = {{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
      for (int c = 0; c < 4; ++c) {
        Piece& child = children[k][c];
        for (int i = 0; i < 3; ++i) {
          const int at = shape[c][i];
          child.corner[i] = at < 3 ? parent.corner[at] : m[at - 3];
          child.distance[i] = at < 3 ? parent.distance[at] : f[at - 3].distance;
          if (at >= 3) add_candidate(child, f[at - 3].triangle);
        }
        for (int p = 0; p < parent.candidate_count; ++p) add_candidate(child, parent.candidates[p]);
        bound(child, closest);
      }
    });
    result.distance_queries += 3 * batch.size();
    result.triangles_split += batch.size();
    for (const auto& three : midpoints) {
      for (const auto& [x, f] : three) raise_lower(x, f);
    }
    for (auto& four : children) {
      for (Piece& child : four) keep(std::move(child));
    }
  }
  result.upper = std::max({result.lower, settled, heap.empty() ? 0.0 : heap.front().upper});
  result.seconds = watch.seconds();
  return result;
}

}  // namespace roving
