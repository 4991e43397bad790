// Exact methods against their libraries' raw limits (exact_throughput.h).
#include "exact_throughput.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "roving/core/geometry.h"
#include "roving/reference_cgal/cgal_reference.h"
#include "roving/reference_embree/embree_reference.h"
#include "roving/registry/method_registry.h"

namespace roving {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// The samples sorted along a Z-order curve (Morton codes of their positions), and where each came from.
SampleSet morton_sorted(const SampleSet& samples, std::vector<std::size_t>& order) {
  BoundingBox box;
  for (const Vec3& p : samples.positions) box.extend(p);
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) keyed[k] = {morton_code(samples.positions[k], box), k};
  std::sort(keyed.begin(), keyed.end());
  SampleSet sorted = samples;
  order.resize(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const std::size_t from = order[k] = keyed[k].second;
    sorted.positions[k] = samples.positions[from];
    sorted.normals[k] = samples.normals[from];
    sorted.weights[k] = samples.weights[from];
    sorted.elements[k] = samples.elements[from];
  }
  return sorted;
}

// Whether the answers on the sorted samples, put back, are the same bits as on the samples.
bool same_answers(const DistanceResult& a, const DistanceResult& sorted,
                  const std::vector<std::size_t>& order) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t j = order[k];
    if (a.hit[j] != sorted.hit[k] ||
        std::memcmp(&a.signed_distance[j], &sorted.signed_distance[k], sizeof(double)) != 0)
      return false;
  }
  return true;
}

// The raw answer against the exact one: the same hit flag on >= 99% of the samples and d within
// 1e-5 of the diagonal on >= 99.9% of the common hits (closest: |d|, on every sample). They
// differ where the rule's tolerance decides: a float ray through a vertex slips between its
// triangles (0.3% of the self-test's lines), a line within 1e-6 of the diagonal of an edge.
std::string raw_disagreement(const DistanceResult& exact, const RawRun& raw, Semantics semantics,
                             double diagonal) {
  std::size_t same = 0, common = 0, close = 0;
  for (std::size_t k = 0; k < raw.distance.size(); ++k) {
    const bool raw_hit = !std::isnan(raw.distance[k]);
    same += raw_hit == bool(exact.hit[k]);
    if (!raw_hit || !exact.hit[k]) continue;
    ++common;
    const double d =
        semantics == Semantics::Closest ? std::abs(exact.signed_distance[k]) : exact.signed_distance[k];
    close += std::abs(d - raw.distance[k]) <= 1e-5 * diagonal;
  }
  const std::size_t n = raw.distance.size();
  const bool ok = semantics == Semantics::Closest ? close == n : same >= 0.99 * n && close >= 0.999 * common;
  return ok ? ""
            : fmt::format("{} of {} hit flags and {} of {} distances differ", n - same, n, common - close,
                          common);
}

}  // namespace

ThroughputStudy exact_throughput(const std::vector<ThroughputPair>& pairs, int repeats,
                                 const std::function<void(const std::string&)>& step) {
  ThroughputStudy study;
  ReportTable& t = study.table;
  t.title = "Exact methods against the raw limits of Embree and CGAL";
  t.header = {"pair",        "samples",   "exact method",  "raw limit",     "build ms",  "raw build ms",
              "build / raw", "samples/s", "Morton-sorted", "raw samples/s", "time / raw"};
  t.settings = fmt::format(
      "Each exact method (the shared rule of roving/core/normal_line.h: bit for bit the same answers by "
      "Embree and CGAL) against the library's own query on the same samples and lines, 2 threads, medians "
      "of {} interleaved runs: Embree's robust triangle BVH with rtcIntersect1 (first hit: one ray from x "
      "+ h n along -n over 2h; nearest: one ray each way from x over h) and rtcPointQuery with a "
      "closest-point callback; CGAL 5.5's AABB tree with first_intersection on rays and closest_point. "
      "Raw queries ignore the tolerance, ties and edge-on triangles; they were checked against the exact "
      "answers first (the same hit flag on >= 99%: raw rays slip between the triangles at 0.3% of the "
      "self-test's vertices; d within 1e-5 of the diagonal on >= 99.9% of common hits; closest on every "
      "sample). Samples are taken in their own order (the faces' or vertices' order in the file); "
      "Morton-sorted: the same samples stored sorted along a Z-order curve beforehand (the sort not "
      "timed), checked to give the same answers bit for bit. Time / raw: our query time over the raw "
      "query's, both in the samples' own order. Builds: our Embree BVH over widened boxes at low quality "
      "(Embree's Morton builder), the raw triangle BVH at Embree's default (medium).",
      repeats);
  const Semantics all[] = {Semantics::FirstHit, Semantics::Nearest, Semantics::Closest};
  for (const ThroughputPair& pair : pairs) {
    step(fmt::format("throughput: {}", pair.name));
    const double diagonal = pair.test.bounding_box().diagonal();
    std::vector<std::size_t> order;
    const SampleSet sorted = morton_sorted(pair.samples, order);
    for (const char* library : {"embree", "cgal"}) {
      for (const Semantics semantics : all) {
        const std::string method_name = fmt::format("{} {}", library, to_string(semantics));
        auto method = make_method(library);
        const DistanceOptions options{semantics, pair.max_error};
        const auto raw_run = [&] {
          return std::string(library) == "embree"
                     ? raw_embree_queries(pair.test, pair.samples, semantics, pair.max_error)
                     : raw_cgal_queries(pair.test, pair.samples, semantics, pair.max_error);
        };
        std::vector<double> build, query, morton, raw_build, raw_query;
        DistanceResult exact, exact_sorted;
        RawRun raw;
        for (int r = 0; r < repeats; ++r) {
          build.push_back(method->build(pair.test));
          exact = method->measure(pair.samples, options);
          query.push_back(exact.query_seconds);
          exact_sorted = method->measure(sorted, options);
          morton.push_back(exact_sorted.query_seconds);
          raw = raw_run();
          raw_build.push_back(raw.build_seconds);
          raw_query.push_back(raw.query_seconds);
          if (r > 0) continue;
          std::string why = raw_disagreement(exact, raw, semantics, diagonal);
          if (!same_answers(exact, exact_sorted, order)) why += " Morton order changed answers";
          if (!why.empty()) {
            study.failures.push_back(fmt::format("throughput, {}, {}: {}", pair.name, method_name, why));
            break;
          }
        }
        const std::string raw_name =
            std::string(library) == "embree"
                ? (semantics == Semantics::Closest ? "rtcPointQuery" : "rtcIntersect1")
                : (semantics == Semantics::Closest ? "closest_point" : "first_intersection");
        if (query.size() < static_cast<std::size_t>(repeats)) {
          t.rows.push_back(
              {pair.name, fmt::format("{}", pair.samples.size()), method_name, raw_name, "check failed"});
          continue;
        }
        const double n = static_cast<double>(pair.samples.size());
        t.rows.push_back({pair.name, fmt::format("{}", pair.samples.size()), method_name, raw_name,
                          figure(1e3 * median(build), 1), figure(1e3 * median(raw_build), 1),
                          figure(median(build) / median(raw_build), 2),
                          fmt::format("{:.3g}", n / median(query)), fmt::format("{:.3g}", n / median(morton)),
                          fmt::format("{:.3g}", n / median(raw_query)),
                          figure(median(query) / median(raw_query), 2)});
      }
    }
  }
  return study;
}

}  // namespace roving
