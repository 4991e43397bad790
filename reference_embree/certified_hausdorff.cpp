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
#include "triangle_piece.h"

namespace roving {

HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap,
                                      const ProgressFn& progress) {
  return certified_hausdorff(a, b, max_gap, 0, a.triangle_count(), progress);
}

HausdorffInterval certified_hausdorff(const TriangleMesh& a, const TriangleMesh& b, double max_gap,
                                      std::size_t first, std::size_t last, const ProgressFn& progress) {
  if (a.triangle_count() == 0) {
    throw Error("certified Hausdorff distance: expected two meshes with triangles, found an empty one");
  }
  CertifiedHausdorff bound(b, max_gap);
  bound.add(a, first, last, progress);
  return bound.interval();
}

CertifiedHausdorff::CertifiedHausdorff(const TriangleMesh& b, double max_gap) : max_gap_(max_gap) {
  if (b.triangle_count() == 0) {
    throw Error("certified Hausdorff distance: expected two meshes with triangles, found an empty one");
  }
  if (!(max_gap > 0) || !std::isfinite(max_gap)) {
    throw Error(fmt::format("--hausdorff-bound: expected a positive finite gap, found {}", max_gap));
  }
  const Stopwatch watch;
  closest_ = std::make_unique<ClosestPoints>(b);
  for (const Vec3& p : b.positions()) largest_coordinate_ = std::max(largest_coordinate_, p.cwiseAbs().maxCoeff());
  result_.seconds = watch.seconds();
}

CertifiedHausdorff::~CertifiedHausdorff() = default;

HausdorffInterval CertifiedHausdorff::interval() const {
  if (!added_) throw Error("certified Hausdorff distance: no triangles of A were given");
  // Every distance above is the kernel's, within its bound of the exact one.
  const double error = closest_point_error_bound(largest_coordinate_);
  HausdorffInterval widened = result_;
  widened.lower = std::max(0.0, result_.lower - error);
  widened.upper = result_.upper + error;
  return widened;
}

void CertifiedHausdorff::add(const TriangleMesh& a, std::size_t first, std::size_t last, const ProgressFn& progress) {
  if (a.triangle_count() == 0) {
    throw Error("certified Hausdorff distance: expected two meshes with triangles, found an empty one");
  }
  if (first > last || last > a.triangle_count()) {
    throw Error(fmt::format("certified Hausdorff distance: triangles [{}, {}) are not within A's {}", first, last,
                            a.triangle_count()));
  }
  const Stopwatch watch;
  const ClosestPoints& closest = *closest_;
  const double max_gap = max_gap_;
  HausdorffInterval& result = result_;
  added_ = true;
  // Every vertex of A's triangles: its distance to B (a lower bound), its closest triangle (a candidate).
  const auto& positions = a.positions();
  const auto& triangles = a.triangles();
  std::vector<bool> used = a.vertex_referenced();
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (used[v]) largest_coordinate_ = std::max(largest_coordinate_, positions[v].cwiseAbs().maxCoeff());
  }
  const bool whole = first == 0 && last == a.triangle_count();
  if (!whole) {
    used.assign(positions.size(), false);
    for (std::size_t t = first; t < last; ++t) {
      for (const int v : triangles[t]) used[v] = true;
    }
  }
  std::vector<ClosestPoints::Found> at_vertex(positions.size());
  constexpr std::size_t kVertexBlock = 65536;  // a progress report (a chance to stop) per block
  for (std::size_t from = 0; from < positions.size(); from += kVertexBlock) {
    const std::size_t to = std::min(positions.size(), from + kVertexBlock);
    tbb::parallel_for(from, to, [&](std::size_t v) {
      if (used[v]) at_vertex[v] = closest.query(positions[v]);
    });
    if (progress) progress("vertices", to, positions.size());
  }
  result.distance_queries +=
      whole ? positions.size() : static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  // The first point found sets the lower end even at distance 0, so that the farthest point
  // reported is always a point of A (never the interval's initial origin).
  const auto raise_lower = [&](const Vec3& x, const ClosestPoints::Found& f) {
    if (f.distance > result.lower || !attained_) {
      result.lower = f.distance, result.lower_point = x, result.lower_closest = f.point;
      attained_ = true;
    }
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
    tbb::parallel_for(std::size_t{0}, batch.size(),
                      [&](std::size_t k) { children[k] = split(batch[k], closest, midpoints[k]); });
    result.distance_queries += 3 * batch.size();
    result.triangles_split += batch.size();
    for (const auto& three : midpoints) {
      for (const auto& [x, f] : three) raise_lower(x, f);
    }
    for (auto& four : children) {
      for (Piece& child : four) keep(std::move(child));
    }
    if (progress) progress("pieces", result.triangles_split, result.triangles_split + heap.size());
  }
  // The parts before this one were settled within the gap of a lower bound no larger than today's.
  result.upper = std::max({result.upper, result.lower, settled, heap.empty() ? 0.0 : heap.front().upper});
  result.seconds += watch.seconds();
}

}  // namespace roving
