#include "mpeg_study.h"

#include <fmt/format.h>

#include <cmath>

#include "decimate.h"
#include "roving/core/error.h"
#include "roving/core/confidence.h"
#include "roving/core/normalise.h"
#include "roving/core/statistics.h"
#include "roving/core/stopwatch.h"
#include "roving/mpeg/mmetric_sampling.h"
#include "roving/mpeg/mpeg_points.h"
#include "roving/mpeg/point_cloud_psnr.h"
#include "roving/mpeg/surface_psnr.h"
#include "roving/reference_embree/certified_hausdorff.h"
#include "roving/registry/method_registry.h"

namespace roving {
namespace {

constexpr double kPeak = 1023;  // the 10-bit grid's, given to both figures

// `mesh` on the 10-bit grid: longest side 1023, every coordinate rounded to a multiple of `step`.
TriangleMesh on_grid(const TriangleMesh& mesh, const Normalisation& grid, double step) {
  const TriangleMesh placed = apply(grid, mesh);
  std::vector<Vec3> positions = placed.positions().to_vector();
  for (Vec3& p : positions) p = (p / step).array().round().matrix() * step;
  return TriangleMesh(std::move(positions), placed.triangles());
}

// `mesh` decimated to about 1 / `fraction` of its triangles: the quadric decimater removes two at a
// collapse inside the surface and one on a boundary, so it may reach only the count next to it.
TriangleMesh decimated(const TriangleMesh& mesh, std::size_t fraction) {
  const std::size_t target = mesh.triangle_count() / fraction;
  try {
    return decimate_quadric(mesh, target);
  } catch (const Error&) {
    return decimate_quadric(mesh, target + 1);
  }
}

std::string psnr_text(double psnr) { return std::isfinite(psnr) ? fmt::format("{:.2f}", psnr) : "inf"; }

std::string interval_text(const std::optional<Interval>& squared) {
  if (!squared) return "N/A";
  return fmt::format("[{}, {}]", psnr_text(geometry_psnr(squared->upper, kPeak)),
                     psnr_text(geometry_psnr(squared->lower, kPeak)));
}

// D1 and D2 of A's surface against B's: area samples, closest points by Embree, the certified
// Hausdorff.
SurfaceFigures surface_figure(const TriangleMesh& from, const TriangleMesh& to, std::size_t samples, double h,
                         double hausdorff_gap) {
  SampleSpec spec;
  spec.kind = SampleSpec::Kind::Area;
  spec.count = samples;
  const SampleSet set = make_samples(from, spec);
  auto embree = make_method("embree");
  DistanceOptions options{Semantics::Closest, h};
  options.faces = true;
  const DistanceResult d = measure_distances(*embree, to, set, options);
  const Statistics statistics = compute_statistics(d.signed_distance, d.hit, set.weights, h);
  const SamplingIntervals intervals = sampling_intervals(d.signed_distance, d.hit, h);
  const HausdorffInterval hausdorff = certified_hausdorff(from, to, hausdorff_gap);
  return surface_figures(set, d, correspondences(set, to, d, Semantics::Closest), to, statistics, &intervals,
                         Interval{hausdorff.lower, hausdorff.upper}, h);
}

}  // namespace

MpegStudy mpeg_study(const std::vector<std::pair<std::string, TriangleMesh>>& models, bool quick,
                     const std::function<void(const std::string&)>& step) {
  MpegStudy study;
  ReportTable& table = study.tables.emplace_back();
  const std::size_t samples = quick ? 20000 : 200000;
  table.title = "MPEG's D1 / D2: mmetric's sampled figures against the surfaces' own";
  table.settings = fmt::format(
      "Each model on a 10-bit grid (longest side 1023, coordinates rounded) against a codec-like copy; peak 1023 "
      "for every PSNR; the worse direction's figure. Sampled: mmetric 1.1.7 `compare --mode pcc` as roving "
      "reproduces it (tests/mpeg_test.cpp holds it to mmetric's output). Surfaces: D1 and D2 of every point of "
      "one surface against the other (Embree, closest point, {} area samples a direction, 95% interval; D2 "
      "along the other surface's normal at the closest point) and the certified Hausdorff PSNR interval.",
      samples);
  table.header = {"model",           "copy",        "triangles A / B",       "samples A / B", "sampled D1 PSNR",
                  "sampled D2 PSNR", "surfaces' D1 PSNR [95%]", "sampled - surfaces' D1, dB", "surfaces' D2 PSNR [95%]",
                  "sampled Hausdorff PSNR",
                  "certified Hausdorff PSNR", "sampled, s", "surfaces, s"};
  for (const auto& [name, mesh] : models) {
    const Normalisation grid = normalisation_of(mesh, 1023.0);
    const TriangleMesh a = on_grid(mesh, grid, 1);
    std::vector<std::pair<std::string, TriangleMesh>> copies;
    copies.emplace_back("8-bit positions", on_grid(mesh, grid, 4));
    copies.emplace_back("decimated to 1/4", on_grid(decimated(mesh, 4), grid, 1));
    if (!quick) copies.emplace_back("decimated to 1/16", on_grid(decimated(mesh, 16), grid, 1));
    for (const auto& [copy, b] : copies) {
      step(fmt::format("MPEG: {} against its copy, {}", name, copy));
      Stopwatch watch;
      MpegRules rules;
      rules.resolution = kPeak;
      rules.mmetric = true;
      const MpegPoints a_points = mpeg_points(mmetric_samples(a, name), name, MpegReading{true, true});
      const MpegPoints b_points = mpeg_points(mmetric_samples(b, copy), copy, MpegReading{true, true});
      const MpegFigures sampled = mpeg_point_cloud_figures(a_points, b_points, rules, name);
      const double sampled_seconds = watch.seconds();

      watch = Stopwatch();
      BoundingBox both = a.bounding_box();
      both.extend(b.bounding_box().min);
      both.extend(b.bounding_box().max);
      const double h = 0.05 * both.diagonal(), gap = 1e-4 * both.diagonal();
      const SurfaceFigures surfaces = worse(surface_figure(a, b, samples, h, gap), surface_figure(b, a, samples, h, gap));
      const double surface_seconds = watch.seconds();

      const MpegDirection w = sampled.symmetric();
      const double sampled_d1 = geometry_psnr(w.d1_mse, kPeak), surface_d1_psnr = geometry_psnr(surfaces.d1_mse, kPeak);
      table.rows.push_back({name, copy, fmt::format("{} / {}", a.triangle_count(), b.triangle_count()),
                            fmt::format("{} / {}", a_points.size(), b_points.size()), psnr_text(sampled_d1),
                            psnr_text(geometry_psnr(w.d2_mse, kPeak)),
                            psnr_text(surface_d1_psnr) + " " + interval_text(surfaces.d1_mse_interval),
                            fmt::format("{:+.2f}", sampled_d1 - surface_d1_psnr),
                            psnr_text(geometry_psnr(surfaces.d2_mse, kPeak)) + " " +
                                interval_text(surfaces.d2_mse_interval),
                            psnr_text(geometry_psnr(w.d1_hausdorff, kPeak)), interval_text(surfaces.hausdorff),
                            fmt::format("{:.2f}", sampled_seconds), fmt::format("{:.2f}", surface_seconds)});
      const std::string key = fmt::format("mpeg/{}/{}/embree/", name, copy);
      study.figures[key + "sampled_d1_psnr"] = sampled_d1;
      study.figures[key + "sampled_d2_psnr"] = geometry_psnr(w.d2_mse, kPeak);
      study.figures[key + "surface_d1_psnr"] = surface_d1_psnr;
      study.figures[key + "surface_d2_psnr"] = geometry_psnr(surfaces.d2_mse, kPeak);
    }
  }
  study.notes =
      "What the differences mean. mmetric's figure pairs each sample of one mesh with the nearest *sample* of "
      "the other, not with the other surface, so the spacing between samples sits in every squared distance: "
      "the column \"sampled - surfaces' D1\" is how much of the reported PSNR is the sampling rather than the "
      "codec. It is small where the copy keeps the mesh's triangles (coarser positions) and large where the "
      "copy's triangles are large, because mmetric samples each triangle at most two subdivisions deep: a "
      "decimated copy (what a base mesh is) is sampled coarsely, and its sampled D1 says "
      "more about its triangles' size than about how far it lies from the original. D2 measures along the other "
      "sample's normal, which removes most of the spacing on flat and smooth parts: read it beside the surfaces' "
      "own D2 (the closest distance's component along the other surface's normal there; equal to the surfaces' "
      "D1 wherever the closest point lies inside a face, smaller where it lies on an edge or a corner). The sampled Hausdorff PSNR is the farthest sample from the "
      "other's samples: it can lie above the certified interval (the samples missed the farthest point of the "
      "surface) or below it (spacing added to it). Figures of two codecs at one sampling compare; figures across "
      "sampling densities, or against a figure computed another way, do not. The surfaces' D1, with its "
      "interval, does not depend on how either mesh was sampled.\n";
  return study;
}

}  // namespace roving
