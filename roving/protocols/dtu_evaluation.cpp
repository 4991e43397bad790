// DTU's evaluation on a pair (dtu_evaluation.h): its files read and checked, the protocol run, its
// exact figures where it measures.
#include "roving/protocols/dtu_evaluation.h"

#include <fmt/format.h>

#include <cmath>

#include "roving/core/error.h"
#include "roving/core/stopwatch.h"
#include "roving/formats/images_and_matlab/matlab_file.h"

namespace roving {
namespace {

void require_finite(const MatlabArray<double>& array, const std::string& path, const char* name) {
  for (const double v : array.values) {
    if (!std::isfinite(v))
      throw Error(fmt::format("{}: variable '{}' holds {}; expected finite numbers", path, name, v));
  }
}

std::string dims_text(const std::vector<std::size_t>& dims) {
  std::string text;
  for (const std::size_t d : dims) text += (text.empty() ? "" : " x ") + std::to_string(d);
  return text.empty() ? "no dimensions" : text;
}

// ObsMask<scan>_10.mat: ObsMask (a 3-D logical array), BB (2 x 3: the box's corners as rows) and
// Res (the voxel side), as DTU's MATLAB evaluation writes them.
DtuObservationMask read_dtu_mask(const std::string& path) {
  DtuObservationMask mask;
  MatlabArray<std::uint8_t> observed = read_matlab_mask(path, "ObsMask");
  if (observed.dims.size() != 3) {
    throw Error(fmt::format("{}: ObsMask is {}; expected a 3-D array", path, dims_text(observed.dims)));
  }
  for (int a = 0; a < 3; ++a) mask.dims[a] = observed.dims[a];
  mask.observed = std::move(observed.values);
  const MatlabArray<double> box = read_matlab_numbers(path, "BB");
  if (box.dims != std::vector<std::size_t>{2, 3}) {
    throw Error(fmt::format("{}: BB is {}; expected 2 x 3 (the box's two corners as rows)", path,
                            dims_text(box.dims)));
  }
  require_finite(box, path, "BB");
  for (int a = 0; a < 3; ++a) {
    mask.box_min[a] = box.values[2 * a];  // MATLAB's order: BB(1, a) then BB(2, a)
    mask.box_max[a] = box.values[2 * a + 1];
  }
  const MatlabArray<double> resolution = read_matlab_numbers(path, "Res");
  if (resolution.values.size() != 1) {
    throw Error(fmt::format("{}: Res is {}; expected one number", path, dims_text(resolution.dims)));
  }
  require_finite(resolution, path, "Res");
  mask.resolution = resolution.values[0];
  if (!(mask.resolution > 0))
    throw Error(fmt::format("{}: Res is {}; expected a voxel side > 0", path, mask.resolution));
  return mask;
}

// Plane<scan>.mat: P, the ground plane's four coefficients; P . (x, y, z, 1) > 0 above it.
std::array<double, 4> read_dtu_plane(const std::string& path) {
  const MatlabArray<double> p = read_matlab_numbers(path, "P");
  if (p.values.size() != 4) {
    throw Error(fmt::format("{}: P is {}; expected the plane's 4 coefficients", path, dims_text(p.dims)));
  }
  require_finite(p, path, "P");
  return {p.values[0], p.values[1], p.values[2], p.values[3]};
}

}  // namespace

DtuFiles read_dtu_files(const DtuPlan& plan) {
  return {read_dtu_mask(plan.obs_mask), read_dtu_plane(plan.plane)};
}

DtuReport dtu_report(const Model& ground_truth, const Model& reconstruction, const DtuPlan& plan,
                     const DtuFiles& files, const ProgressFn& progress) {
  const Stopwatch watch;
  DtuReport report;
  report.obs_mask = plan.obs_mask;
  report.plane = plan.plane;
  const auto refuse = [](const Model& model, const char* role) {
    return Error(fmt::format("{}: --protocol dtu takes a mesh or a point cloud as {}; found a {} model",
                             model.path(), role, to_string(model.type)));
  };
  const std::vector<Vec3>* truth = nullptr;
  std::vector<Vec3> mesh_vertices;
  if (ground_truth.type == ModelType::Points) {
    truth = &ground_truth.points.positions;
  } else if (ground_truth.type == ModelType::Mesh) {
    mesh_vertices =
        ground_truth.mesh.mesh.positions().to_vector();  // the script reads a mesh's file as its vertices
    truth = &mesh_vertices;
  } else {
    throw refuse(ground_truth, "REF (the ground truth)");
  }
  std::size_t samples = 0;
  if (reconstruction.type == ModelType::Mesh) {
    const std::vector<Vec3> points =
        dtu_mesh_points(reconstruction.mesh.mesh, reconstruction.path(), plan.options.density, &samples);
    report.figures = dtu_figures(points, *truth, files.mask, files.plane, plan.options, progress);
  } else if (reconstruction.type == ModelType::Points) {
    report.figures =
        dtu_figures(reconstruction.points.positions, *truth, files.mask, files.plane, plan.options, progress);
  } else {
    throw refuse(reconstruction, "TEST (the reconstruction)");
  }
  report.figures.samples = samples;
  report.seconds = watch.seconds();
  return report;
}

void set_exact_within_region(DtuReport& report, const DtuPlan& plan, const DtuFiles& files,
                             const CorrespondenceSet& reference_to_test,
                             const CorrespondenceSet& test_to_reference,
                             const std::vector<double>& thresholds, bool area_uniform) {
  const DtuRegion region(files.mask, files.plane, plan.options.patch);
  const auto mark = [&](const SampleSet& samples, auto&& inside, std::size_t& counted, std::size_t& total) {
    std::vector<std::uint8_t> marks(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) marks[k] = inside(samples.positions[k]) ? 1 : 0;
    counted = static_cast<std::size_t>(std::count(marks.begin(), marks.end(), 1));
    total = samples.size();
    return marks;
  };
  const std::vector<std::uint8_t> above = mark(
      *reference_to_test.samples, [&](const Vec3& p) { return region.above(p); },
      report.exact_reference_counted, report.exact_reference_samples);
  const std::vector<std::uint8_t> observed = mark(
      *test_to_reference.samples, [&](const Vec3& p) { return region.observed(p); },
      report.exact_test_counted, report.exact_test_samples);
  CorrespondenceSet completeness = reference_to_test, accuracy = test_to_reference;
  completeness.region = &above;
  accuracy.region = &observed;
  report.exact = reconstruction_figures(completeness, accuracy, thresholds, area_uniform);
  const auto below_cap = [&](const CorrespondenceSet& set, std::vector<std::uint8_t> marks) {
    for (std::size_t k = 0; k < marks.size(); ++k) {
      marks[k] =
          marks[k] && set.result->hit[k] && std::abs(set.result->signed_distance[k]) < plan.options.max_dist;
    }
    return marks;
  };
  const std::vector<std::uint8_t> above_capped = below_cap(reference_to_test, above),
                                  observed_capped = below_cap(test_to_reference, observed);
  completeness.region = &above_capped;
  accuracy.region = &observed_capped;
  report.exact_below_cap = reconstruction_figures(completeness, accuracy, thresholds, area_uniform);
}

}  // namespace roving
