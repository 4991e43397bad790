#include "reconstruction_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "decimate.h"
#include "roving/core/normalise.h"
#include "roving/core/stopwatch.h"
#include "roving/reconstruction/dtu_protocol.h"
#include "roving/reconstruction/reconstruction_figures.h"
#include "roving/reconstruction/tanks_and_temples_protocol.h"
#include "roving/reference_embree/certified_area_within.h"
#include "roving/registry/method_registry.h"
#include "roving/representations/voxel_surface.h"
#include "voxelize.h"

namespace roving {
namespace {

constexpr double kLongestSide = 200;  // millimetres: a DTU object's size
constexpr double kTau = 0.5;          // the F-score's threshold, mm (0.25% of the longest side)

// Every vertex moved along its normal by Gaussian noise of deviation `sigma` (a fixed seed).
TriangleMesh noisy(const TriangleMesh& mesh, double sigma) {
  std::mt19937_64 random(1);
  std::normal_distribution<double> noise(0, sigma);
  const std::vector<Vec3> normals = mesh.vertex_normals();
  std::vector<Vec3> positions = mesh.positions().to_vector();
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] += noise(random) * normals[i];
  return TriangleMesh(std::move(positions), mesh.triangles().to_vector());
}

// The triangles whose centroid lies within `radius` of the vertex farthest along +x left out (a
// part the scanner or the cameras never saw), and the vertices they leave unused.
TriangleMesh holed(const TriangleMesh& mesh, double radius) {
  const auto& positions = mesh.positions();
  const Vec3 centre = *std::max_element(positions.begin(), positions.end(),
                                        [](const Vec3& p, const Vec3& q) { return p.x() < q.x(); });
  std::vector<int> index(positions.size(), -1);
  std::vector<Vec3> kept_positions;
  std::vector<Triangle> kept;
  for (const Triangle& t : mesh.triangles()) {
    const Vec3 centroid = (positions[t[0]] + positions[t[1]] + positions[t[2]]) / 3;
    if ((centroid - centre).norm() <= radius) continue;
    Triangle u;
    for (int c = 0; c < 3; ++c) {
      if (index[t[c]] < 0) {
        index[t[c]] = static_cast<int>(kept_positions.size());
        kept_positions.push_back(positions[t[c]]);
      }
      u[c] = index[t[c]];
    }
    kept.push_back(u);
  }
  return TriangleMesh(std::move(kept_positions), std::move(kept));
}

// A mask of DTU's layout with every voxel observed over `box` (and a little more), so that the
// protocol keeps every point: the table compares the rest of its pipeline with the exact figures.
DtuObservationMask everything_observed(const BoundingBox& box) {
  DtuObservationMask mask;
  mask.resolution = 10;
  mask.box_min = box.min - Vec3::Constant(mask.resolution);
  mask.box_max = box.max + Vec3::Constant(mask.resolution);
  for (int a = 0; a < 3; ++a)
    mask.dims[a] = static_cast<std::size_t>(std::ceil((mask.box_max[a] - mask.box_min[a]) / mask.resolution)) + 2;
  mask.observed.assign(mask.dims[0] * mask.dims[1] * mask.dims[2], 1);
  return mask;
}

// A crop volume of Tanks and Temples' layout around all of `box` (and a little more), so that only
// the rest of its pipeline differs.
CropVolume everything_cropped(const BoundingBox& box) {
  const Vec3 low = box.min - Vec3::Constant(1), high = box.max + Vec3::Constant(1);
  return CropVolume(2, low.z(), high.z(), {{low.x(), low.y(), 0}, {high.x(), low.y(), 0}, {high.x(), high.y(), 0},
                                           {low.x(), high.y(), 0}},
                    "the study's crop");
}

// The exact figures: `samples` area samples a direction, closest points by Embree with their faces,
// and F-score's certified bounds.
struct Exact {
  ReconstructionFigures figures;
  double seconds = 0, certified_seconds = 0;
};

Exact exact_figures(const TriangleMesh& truth, const TriangleMesh& copy, std::size_t samples, double min_length) {
  const Stopwatch watch;
  SampleSpec spec;
  spec.kind = SampleSpec::Kind::Area;
  spec.count = samples;
  const SampleSet on_truth = make_samples(truth, spec), on_copy = make_samples(copy, spec);
  auto embree = make_method("embree");
  DistanceOptions options{Semantics::Closest, kLongestSide};
  options.faces = true;
  const DistanceResult completeness = measure_distances(*embree, copy, on_truth, options);
  const DistanceResult accuracy = measure_distances(*embree, truth, on_copy, options);
  Exact exact;
  exact.figures =
      reconstruction_figures({&on_truth, &completeness, &copy}, {&on_copy, &accuracy, &truth}, {kTau}, true);
  exact.seconds = watch.seconds();
  const Stopwatch certified;
  const auto bounds = [&](const TriangleMesh& a, const TriangleMesh& b) {
    const AreaWithin w = certified_area_within(a, b, {kTau}, min_length, 0, a.triangle_count());
    return std::vector<ReconstructionFigures::Bounds>{{w.lower(0), w.upper(0)}};
  };
  set_certified_shares(exact.figures, bounds(copy, truth), bounds(truth, copy));
  exact.certified_seconds = certified.seconds();
  return exact;
}

std::string with_interval(const Estimate& e, int digits) {
  return fmt::format("{} [{}, {}]", figure(e.value, digits), figure(e.lower, digits), figure(e.upper, digits));
}

// The first run's figure and the range over the runs' seeds.
std::string with_range(const DtuFigures& dtu, double DtuRun::*member) {
  double low = dtu.runs.front().*member, high = low;
  for (const DtuRun& run : dtu.runs) low = std::min(low, run.*member), high = std::max(high, run.*member);
  return fmt::format("{} ({} to {})", figure(dtu.runs.front().*member, 4), figure(low, 4), figure(high, 4));
}

}  // namespace

ReconstructionStudy reconstruction_study(const std::vector<std::pair<std::string, TriangleMesh>>& models, bool quick,
                                         const std::function<void(const std::string&)>& step) {
  ReconstructionStudy study;
  ReportTable& table = study.tables.emplace_back();
  const std::size_t samples = quick ? 20000 : 200000;
  DtuOptions dtu_options;
  dtu_options.density = quick ? 1.0 : 0.2;
  dtu_options.runs = 5;
  const double certified_piece = quick ? 1e-3 : 1e-4;  // certified bounds: the smallest piece, of the diagonal
  const TanksAndTemplesOptions tnt_options{kTau, kTau / 2, 5};
  table.title = "Reconstruction figures: DTU's and Tanks and Temples' protocols against the surfaces' own";
  table.settings = fmt::format(
      "Each model scaled to longest side {:g} (millimetres, a DTU object's size) is the ground truth (REF); "
      "the copies stand in for reconstructions (TEST). DTU: DTUeval-python's pipeline as roving reproduces it "
      "(tests/dtu_test.cpp holds it to the script's output): both meshes sampled by its rule at density {:g} mm, "
      "the reconstruction thinned at that radius after a seeded shuffle, nearest *points* both ways, distances "
      "of {:g} mm or more left out; a mask observing everything and no ground plane, so that only the pipeline "
      "differs; the first of {} seeds' figure, then their range. Tanks and Temples: its toolbox's EvaluateHisto "
      "as roving reproduces it (tests/tnt_test.cpp) on the same points DTU samples (before its thinning), "
      "a crop around everything and no alignment, voxels of tau / 2, precision, recall and F at tau. Exact: every point of one surface against the "
      "other surface (Embree, closest point, {} area samples a direction, 95% interval), F-score at tau = {:g} "
      "mm with its certified bounds (every point of the surfaces, reference_embree/certified_area_within, "
      "pieces down to {:g}% of the diagonal).",
      kLongestSide, dtu_options.density, dtu_options.max_dist, dtu_options.runs, samples, kTau, 100 * certified_piece);
  table.header = {"model",
                  "copy",
                  "triangles REF / TEST",
                  "DTU points REF / TEST thinned",
                  "DTU accuracy, mm (seeds' range)",
                  "exact accuracy, mm [95%]",
                  "DTU completeness, mm (seeds' range)",
                  "exact completeness, mm [95%]",
                  "DTU overall, mm",
                  "exact Chamfer (mean of means), mm [95%]",
                  "exact F at tau [95%]",
                  "certified F at tau",
                  "exact normal consistency",
                  "T&T precision / recall / F at tau",
                  "DTU, s",
                  "T&T, s",
                  "exact, s (certified)"};
  for (const auto& [name, mesh] : models) {
    const TriangleMesh truth = normalised(mesh, kLongestSide);
    const double diagonal = truth.bounding_box().diagonal();
    std::vector<std::pair<std::string, TriangleMesh>> copies;
    copies.emplace_back("noise 0.1% along the normals", noisy(truth, 1e-3 * diagonal));
    copies.emplace_back("a hole of radius 10%", holed(truth, 0.1 * diagonal));
    if (!quick) {
      copies.emplace_back("decimated to 1/16", decimate_quadric(truth, (truth.triangle_count() / 16) & ~std::size_t{1}));
      copies.emplace_back("voxelised at 64", exposed_faces(voxelize_thin(truth, 64)));
    }
    const std::vector<Vec3> truth_points = dtu_mesh_points(truth, name, dtu_options.density);
    for (const auto& [copy_name, copy] : copies) {
      step(fmt::format("reconstruction: {} against its copy, {}", name, copy_name));
      Stopwatch watch;
      BoundingBox both = truth.bounding_box();
      both.extend(copy.bounding_box().min);
      both.extend(copy.bounding_box().max);
      const std::vector<Vec3> copy_points = dtu_mesh_points(copy, copy_name, dtu_options.density);
      const DtuFigures dtu =
          dtu_figures(copy_points, truth_points, everything_observed(both), {0, 0, 0, 1}, dtu_options);
      const double dtu_seconds = watch.seconds();
      watch = Stopwatch();
      const TanksAndTemplesFigures tnt =
          tanks_and_temples_figures(copy_points, truth_points, everything_cropped(both), tnt_options);
      const double tnt_seconds = watch.seconds();
      const Exact exact = exact_figures(truth, copy, samples, certified_piece * diagonal);
      const ReconstructionFigures& f = exact.figures;
      const DtuRun& first = dtu.runs.front();
      table.rows.push_back(
          {name, copy_name, fmt::format("{} / {}", truth.triangle_count(), copy.triangle_count()),
           fmt::format("{} / {}", dtu.ground_truth_points, first.thinned), with_range(dtu, &DtuRun::accuracy),
           with_interval(f.accuracy.mean, 4), with_range(dtu, &DtuRun::completeness),
           with_interval(f.completeness.mean, 4), figure(first.overall, 4), with_interval(f.chamfer_mean_estimate, 4),
           with_interval(f.f_score_estimate[0], 4),
           fmt::format("[{}, {}]", figure(f.f_score_certified[0].lower, 4), figure(f.f_score_certified[0].upper, 4)),
           figure(f.normal_consistency, 4),
           fmt::format("{} / {} / {}", figure(tnt.precision, 4), figure(tnt.recall, 4), figure(tnt.fscore, 4)),
           fmt::format("{:.2f}", dtu_seconds), fmt::format("{:.2f}", tnt_seconds),
           fmt::format("{:.2f} ({:.2f})", exact.seconds, exact.certified_seconds)});
      const std::string key = fmt::format("reconstruction/{}/{}/", name, copy_name);
      study.figures[key + "dtu/accuracy"] = first.accuracy;
      study.figures[key + "dtu/completeness"] = first.completeness;
      study.figures[key + "tnt/precision"] = tnt.precision;
      study.figures[key + "tnt/recall"] = tnt.recall;
      study.figures[key + "tnt/f_score"] = tnt.fscore;
      study.figures[key + "embree/accuracy"] = f.accuracy.mean.value;
      study.figures[key + "embree/completeness"] = f.completeness.mean.value;
      study.figures[key + "embree/f_score"] = f.f_score[0];
      study.figures[key + "embree/f_score_certified_lower"] = f.f_score_certified[0].lower;
      study.figures[key + "embree/f_score_certified_upper"] = f.f_score_certified[0].upper;
      study.figures[key + "embree/normal_consistency"] = f.normal_consistency;
    }
  }
  study.notes =
      "What the differences mean. DTU pairs each kept point with the nearest *point* of the other set, not with "
      "the surface: each such distance is at least the distance to the surface, and the spacing between the "
      "points (its density) adds to it. That spacing is what separates DTU's completeness from the exact one "
      "where the copy lies close to the truth (noise, decimation): the smaller the error, the more of DTU's "
      "figure is sampling. DTU's cap leaves out every distance of 20 mm or more, so a hole counts only up to the "
      "cap: where a hole's distances pass it (a radius of 10% of the diagonal is some 30 mm here), DTU's "
      "completeness falls below the exact one, which integrates over the whole missing area. Where DTU's "
      "accuracy lies below the exact one although no nearest point is nearer than the surface, its points weigh "
      "the surface differently from its area (its grid on each face is scaled to the face's edges, and the "
      "thinning keeps one point per radius), while area samples weigh every square millimetre alike. The "
      "seeded shuffle moves DTU's figures by the range shown; the exact figures do not depend on how either "
      "surface was sampled, and their intervals hold 95% of the time (Chamfer's and F's from the two "
      "directions', docs/reconstruction.md). F's certified bounds hold for every point of both surfaces, not "
      "only for the samples; they are wide where much of the area lies within a piece's size of tau of the "
      "other surface: a decimated copy's large faces, which the 6 splits a triangle may take leave in pieces "
      "of a few tenths of a millimetre, and the voxel copies' steps. Tanks and Temples' F counts points, "
      "not area, and its points are the means of voxels of tau / 2: a mean of noisy points lies nearer the "
      "surface than the points do, while a nearest *point* is never nearer than the surface and the points' "
      "spacing adds to it as in DTU's; where that spacing is not small against tau (the quick run samples "
      "1 mm apart against tau 0.5 mm), it alone puts distances past tau, and precision and recall fall far "
      "below the exact shares. Where the copy's error is near tau (noise, decimation), a small shift of the "
      "distances moves much area across tau, and the two F-scores part most.\n";
  return study;
}

}  // namespace roving
