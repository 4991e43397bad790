// The one interface every distance method implements (references, baselines, the GL methods),
// so that they can be swapped and cross-checked on the same samples.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "roving/core/sample_set.h"
#include "roving/core/stopwatch.h"
#include "roving/core/triangle_mesh.h"

namespace roving {

// What "the distance of a sample x with normal n to M_C" means (DESIGN.md "Definitions").
// Where the normal line meets M_C is decided by one rule for every exact method
// (normal_line.h): closed triangles widened by 1e-6 of M_C's diagonal, so a line through a test
// vertex, along a test edge or by a boundary vertex meets it whatever the rounding.
enum class Semantics {
  // Paper: first surface met by the ray from x + h n along -n, t in [0, 2h]; d = h - t.
  FirstHit,
  // The intersection of the normal line with M_C nearest to x, |d| <= h.
  Nearest,
  // Metro-style: distance to the nearest point c of M_C, signed by (c - x) . n. Always a hit.
  Closest,
};

const char* to_string(Semantics semantics);

// Where exact roving's per-sample cameras are made (--camera-geometry): their triangles put in
// the camera's frame on the CPU threads, or in a compute shader, and drawn (the paper's raster
// pipeline); or each camera's depth evaluated in a compute pass, nothing drawn.
enum class CameraGeometry { Cpu, Gpu, Compute };
const char* to_string(CameraGeometry geometry);
// Parses "cpu", "gpu" or "compute"; throws roving::Error naming --camera-geometry otherwise.
CameraGeometry parse_camera_geometry(const std::string& text);
// Parses "first-hit", "nearest", "closest"; throws roving::Error naming `--semantics` otherwise.
Semantics parse_semantics(const std::string& text);

// h as the user gives it: an absolute length ("0.01") or a percentage of M_R's bounding-box
// diagonal ("5%", the default).
struct MaxErrorSpec {
  double value = 5;
  bool percent_of_diagonal = true;

  double resolve(double diagonal) const { return percent_of_diagonal ? value / 100 * diagonal : value; }
  std::string to_string() const;
};

// Parses VALUE or P%; throws roving::Error naming `--max-error` unless it is a finite number > 0
// (and a percentage <= 100).
MaxErrorSpec parse_max_error(const std::string& text);

// How far a long stage has got ("samples", "views", "cameras"; done of total), for a progress
// display. Called from any thread, possibly at once from several.
using ProgressFn = std::function<void(const char* stage, std::size_t done, std::size_t total)>;

struct DistanceOptions {
  Semantics semantics = Semantics::FirstHit;
  double max_error = 0;  // h: half-height of the view volume, model units, > 0
  // Also report TEST's colour at each hit, for the colour figures: the exact references and the
  // nearest-point baselines give the face each hit lies on (DistanceResult::hit_face; colour.h then
  // takes the colour there), the GL methods draw the colour in the frame buffer beside the depth
  // and the nearest-vertex baselines take their vertex's (hit_colour), where TEST has colour.
  bool colour = false;
  // Also give the face each hit lies on (DistanceResult::hit_face), where the method knows it (the
  // exact references, the nearest-point baselines, the GL methods by the exact rule near their d):
  // for figures at the correspondence, as the reconstruction figures' normal consistency.
  bool faces = false;
};

// How a GL method resolved one sample.
enum class Resolution : std::uint8_t { Unresolved = 0, View = 1, Camera = 2 };

// What a GL method reports beside the distances: the paper's observations (Table 1: views
// rendered plus per-sample cameras), per-sample resolution, and the precision its tolerances
// are derived from.
struct GlReport {
  std::string renderer;                 // backend and GL_RENDERER
  std::size_t views_rendered = 0;       // viewpoint-sampling views drawn (directions with samples)
  std::size_t sample_cameras = 0;       // surface-roving cameras (one-pixel views)
  std::vector<Resolution> resolved_by;  // per sample; Unresolved = no hit
  int views_h = 0, views_v = 0, resolution = 0;
  bool axis_views = false;       // every sample normal was an axis: the 6 axis views were used
  double view_pixel_size = 0;    // model units per view pixel
  double view_depth_step = 0;    // model units per ulp of float depth near 1 in a view
  double camera_half_width = 0;  // half-width of a roving camera's view volume (one pixel)
  double camera_depth_step = 0;  // model units per ulp of float depth near 1 in a roving camera
  CameraGeometry camera_geometry = CameraGeometry::Cpu;  // where the cameras were made
  bool views_culled = true;      // each view drew only what its samples' pixels can show (else whole)
  std::size_t thin_cameras = 0;  // compute pass: cameras whose thin faces the CPU's rule decided
  // Compute pass, where each hit's face was asked (colour, the correspondences): hits whose face
  // the pass chose by the rule, and hits it left to the CPU's (hit_colour.h).
  std::size_t faces_chosen_in_pass = 0, faces_left_to_cpu = 0;
  // Where the cameras' time went: building their batches (CPU threads, beside the draws) and
  // rendering them (GL thread: upload, any compute stage, draw, read back).
  double camera_build_seconds = 0, camera_render_seconds = 0;
  // And the views': preparing (footprint, culling) and reading them (each sample's line) on the
  // CPU threads, beside the drawing; drawing them on the GL thread (draw, read back).
  double view_cpu_seconds = 0, view_draw_seconds = 0;

  // Samples of a streamed REF's earlier blocks, whose resolved_by was let go: how many each way.
  std::array<std::size_t, 3> earlier_resolved{};

  std::size_t observations() const { return views_rendered + sample_cameras; }
  // How many samples were resolved `how`, earlier blocks' included.
  std::size_t resolved(Resolution how) const;
  // Folds in the report of the next block of samples: counts and times add up, and the block's
  // per-sample record is kept as counts alone.
  void add_block(const GlReport& block);
};

// Per-sample output. signed_distance[k] is meaningful only where hit[k] is set.
struct DistanceResult {
  std::vector<double> signed_distance;
  std::vector<std::uint8_t> hit;
  // The face of TEST where each hit lies (DistanceOptions::colour); empty when not asked for
  // or not known. Where the line meets several faces at the chosen d, the lowest index.
  std::vector<std::uint32_t> hit_face;
  // TEST's colour at each hit as the method found it itself (DistanceOptions::colour): a GL
  // method's frame buffer, a vertex baseline's nearest vertex; code values, NaN where there is
  // none; empty when not asked for or not given this way.
  std::vector<Colour> hit_colour;
  // How TEST's colour at each hit is found, for the report: "on the hit's face" (hit_face), "drawn
  // in the frame buffer" or "at the nearest vertex" (hit_colour); empty without colour.
  std::string colour_source;
  double build_seconds = 0;    // acceleration structures, uploads: once per test model
  double query_seconds = 0;    // all samples
  std::optional<GlReport> gl;  // GL methods only

  std::size_t hit_count() const;
};

// Hits by the sign of d: TEST outside REF along its normal (d > 0), inside (d < 0), on it.
struct SignCounts {
  std::size_t positive = 0, negative = 0, zero = 0;
};
SignCounts sign_counts(const DistanceResult& result);

class DistanceMethod {
 public:
  virtual ~DistanceMethod() = default;

  virtual std::string name() const = 0;
  // The semantics this method can compute; the first is its default.
  virtual std::vector<Semantics> supported_semantics() const = 0;

  // Prepares for queries against `test` (kept by reference: it must outlive the method).
  // Returns the build time in seconds.
  virtual double build(const TriangleMesh& test) = 0;

  // Measures every sample; requires build(). Throws roving::Error on bad options
  // (h <= 0 or not finite, unsupported semantics).
  virtual DistanceResult measure(const SampleSet& samples, const DistanceOptions& options) = 0;

  // Samples are answered in runs of this many (1: each alone, as the ray casts and searches
  // are): a sample's answer may depend on its place in its run (a GL camera's tile), never on
  // the other runs' samples, so measuring the samples split at multiples of it gives the
  // answers of one call. 0: every sample's answer depends on them all (views drawn for them all).
  virtual std::size_t independent_run() const { return 1; }

  // Frees what build() made (its BVH, tree or GL scene), so that statistics and output after
  // the query do not hold it too; measure() then needs build() again.
  virtual void release() {}

  bool supports(Semantics semantics) const;

  // Who hears how far measure() has got (empty: nobody).
  void set_progress(ProgressFn progress) { progress_ = std::move(progress); }

 protected:
  ProgressFn progress_;
};

// An answer that names the face of TEST it lies on.
struct FaceHit {
  double distance;
  std::uint32_t face;
};

// measure_each (below) for a `distance_of` that keeps state from one sample to the next: each
// block of consecutive samples calls `make_worker()` for a worker of its own, and the worker's
// `operator()(k)` answers for sample k. Neighbours in sample order are mostly neighbours on the
// surface, so one sample's answer can seed the next one's search. A worker answers
// std::optional<double> or std::optional<FaceHit>; with the latter, `keep_faces` fills hit_face.
template <class MakeWorker>
DistanceResult measure_in_blocks(std::size_t count, const MakeWorker& make_worker,
                                 const ProgressFn& progress = {}, bool keep_faces = false) {
  using Answer = decltype(make_worker()(std::size_t{}));
  constexpr bool answers_faces = std::is_same_v<Answer, std::optional<FaceHit>>;
  const Stopwatch watch;
  DistanceResult result;
  result.signed_distance.assign(count, 0.0);
  result.hit.assign(count, 0);
  if (answers_faces && keep_faces) {
    result.hit_face.assign(count, 0);
    result.colour_source = "on the hit's face";
  }
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      auto distance_of = make_worker();
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        if (const Answer answer = distance_of(k)) {
                          result.hit[k] = 1;
                          if constexpr (answers_faces) {
                            result.signed_distance[k] = answer->distance;
                            if (keep_faces) result.hit_face[k] = answer->face;
                          } else {
                            result.signed_distance[k] = *answer;
                          }
                        }
                      }
                      if (progress) progress("samples", done += range.size(), count);
                    });
  result.query_seconds = watch.seconds();
  return result;
}

// Calls `distance_of(k)` for k in [0, count) on all cores (TBB) and gathers the answers: a value
// is a hit with that signed distance, nullopt a no-hit. query_seconds is the wall time taken.
// `distance_of` must be safe to call from several threads at once. A template, so that the
// per-sample call inlines (std::function cost 4% of an Embree query). `progress` hears of each
// finished block of samples.
template <class DistanceOf>
DistanceResult measure_each(std::size_t count, const DistanceOf& distance_of, const ProgressFn& progress = {},
                            bool keep_faces = false) {
  return measure_in_blocks(
      count, [&] { return std::cref(distance_of); }, progress, keep_faces);
}

// Checks options against `method` and throws roving::Error naming the option on failure.
void validate_options(const DistanceMethod& method, const DistanceOptions& options);

// build() + measure() + release(), with both times filled in.
DistanceResult measure_distances(DistanceMethod& method, const TriangleMesh& test, const SampleSet& samples,
                                 const DistanceOptions& options);

}  // namespace roving
