// The families of figures and their order (figure_families.h).
#include "figure_families.h"

#include <fmt/format.h>

#include <array>

#include "roving/gl_methods/image_based_report.h"
#include "roving/mpeg/mpeg_report.h"
#include "roving/reconstruction/reconstruction_report.h"

namespace roving {
namespace {

// --threshold in model units.
std::vector<double> thresholds_of(const MeasurePlan& plan, double diagonal) {
  std::vector<double> thresholds;
  for (const MaxErrorSpec& tau : plan.thresholds) thresholds.push_back(tau.resolve(diagonal));
  return thresholds;
}

bool area_uniform(const MeasureReport& report) {
  return report.directions[0].samples.kind.rfind("area:", 0) == 0;
}

// The directions' correspondences as the reconstruction figures take them: REF's samples against
// TEST, and TEST's against REF.
std::array<CorrespondenceSet, 2> correspondence_sets(const MeasureReport& report, const Model& a,
                                                     const Model& b) {
  const DirectionReport &ab = report.directions[0], &ba = report.directions[1];
  return {CorrespondenceSet{&ab.samples, &ab.result, &test_surface(b)},
          CorrespondenceSet{&ba.samples, &ba.result, &test_surface(a)}};
}

// The reconstruction figures' certified precision and recall, from the directions' area_within
// bounds (REF's share within tau of TEST is recall's; TEST's of REF, precision's).
void certify_reconstruction(MeasureReport& report) {
  if (!report.reconstruction || !report.symmetric() || !report.directions[0].area_within ||
      !report.directions[1].area_within) {
    return;
  }
  const auto bounds = [](const AreaWithin& w) {
    std::vector<ReconstructionFigures::Bounds> out;
    for (std::size_t k = 0; k < w.thresholds.size(); ++k) out.push_back({w.lower(k), w.upper(k)});
    return out;
  };
  set_certified_shares(*report.reconstruction, bounds(*report.directions[1].area_within),
                       bounds(*report.directions[0].area_within));
}

const FigureFamily kReconstruction = {
    "reconstruction",
    false,
    [](const MeasurePlan& plan, const Model&, const Model&) { return plan.symmetric; },
    [](FamilyInputs& in, MeasureReport& report) {
      const auto [ab, ba] = correspondence_sets(report, in.a, in.b);
      report.reconstruction =
          reconstruction_figures(ab, ba, thresholds_of(in.plan, report.diagonal), area_uniform(report));
      certify_reconstruction(report);
      if (in.plan.certify_thresholds && !in.plan.shard &&
          report.reconstruction->precision_certified.empty()) {
        in.warn(
            {"--certify-thresholds: no certified bounds: they are shares of area, and a point cloud has "
             "none"});
      }
    },
    [](const MeasureReport& r) {
      return r.reconstruction ? reconstruction_lines(*r.reconstruction, r.diagonal) : std::string();
    },
    [](const MeasureReport& r, nlohmann::json& json) {
      if (r.reconstruction) json["reconstruction"] = reconstruction_json(*r.reconstruction);
    }};

// MPEG's figures beside the distances: of two point clouds always, of anything with --pcc (two
// meshes: also D1 and D2 of the surfaces themselves, from the directions' closest points).
const FigureFamily kMpeg = {
    "mpeg",
    false,
    [](const MeasurePlan& plan, const Model& a, const Model& b) {
      return (a.type == ModelType::Points && b.type == ModelType::Points) || plan.pcc_only;
    },
    [](FamilyInputs& in, MeasureReport& report) {
      in.stage = fmt::format("computing MPEG's point-cloud figures of {} and {}", in.a.path(), in.b.path());
      in.progress.stage("MPEG point-cloud figures");
      report.mpeg = mpeg_report(in.a, in.b, in.plan.pcc_resolution, in.plan.pcc_normals);
      if (!in.plan.pcc_only || !report.symmetric()) return;
      std::array<SurfaceFigures, 2> exact;
      for (int i = 0; i < 2; ++i) {
        const DirectionReport& d = report.directions[i];
        std::optional<Interval> hausdorff;
        if (d.hausdorff) hausdorff = Interval{d.hausdorff->lower, d.hausdorff->upper};
        exact[i] =
            surface_figures(d.samples, d.result, *d.correspondences, test_surface(*d.test), d.statistics,
                            d.intervals ? &*d.intervals : nullptr, hausdorff, report.max_error);
      }
      report.mpeg->surface = exact;
    },
    [](const MeasureReport& r) { return r.mpeg ? mpeg_lines(*r.mpeg) : std::string(); },
    [](const MeasureReport& r, nlohmann::json& json) {
      if (r.mpeg) json["mpeg_pcc"] = mpeg_json(*r.mpeg);
    }};

// DTU's evaluation; with --symmetric, the exact figures where it measures too.
const FigureFamily kDtu = {
    "dtu",
    true,
    [](const MeasurePlan& plan, const Model&, const Model&) { return plan.dtu.has_value(); },
    [](FamilyInputs& in, MeasureReport& report) {
      const DtuFiles& files = *in.protocol->dtu;
      in.stage =
          fmt::format("running the DTU protocol on {} (ground truth) and {}", in.a.path(), in.b.path());
      in.progress.stage("DTU protocol");
      report.dtu = dtu_report(in.a, in.b, *in.plan.dtu, files, in.progress.callback());
      in.progress.clear();
      if (!report.reconstruction) return;
      const auto [ab, ba] = correspondence_sets(report, in.a, in.b);
      set_exact_within_region(*report.dtu, *in.plan.dtu, files, ab, ba, report.reconstruction->thresholds,
                              area_uniform(report));
    },
    [](const MeasureReport& r) { return r.dtu ? dtu_lines(*r.dtu) : std::string(); },
    [](const MeasureReport& r, nlohmann::json& json) {
      if (r.dtu) json["dtu_protocol"] = dtu_json(*r.dtu);
    }};

// Tanks and Temples' evaluation, after run.py's registration where a trajectory was given; with
// --symmetric, the exact figures within the crop too.
const FigureFamily kTanksAndTemples = {
    "tanks-and-temples",
    true,
    [](const MeasurePlan& plan, const Model&, const Model&) { return plan.tnt.has_value(); },
    [](FamilyInputs& in, MeasureReport& report) {
      ProtocolInputs& protocol = *in.protocol;
      in.stage = fmt::format("running the Tanks and Temples protocol on {} (ground truth) and {}",
                             in.a.path(), in.b.path());
      in.progress.stage("Tanks and Temples protocol");
      report.tnt = tanks_and_temples_report(in.a, in.b, *in.plan.tnt, *protocol.tnt, in.progress.callback());
      in.progress.clear();
      if (!protocol.tnt_registrations.empty()) {
        TanksAndTemplesRegistrationRun& first = protocol.tnt_registrations.front();
        first.precision = report.tnt->figures.precision;
        first.recall = report.tnt->figures.recall;
        first.fscore = report.tnt->figures.fscore;
        report.tnt->registrations = std::move(protocol.tnt_registrations);
        report.tnt->registration_seconds = protocol.tnt_registration_seconds;
      }
      if (!report.reconstruction) return;
      const auto [ab, ba] = correspondence_sets(report, in.a, in.b);
      set_exact_within_crop(*report.tnt, *protocol.tnt, ab, ba, report.reconstruction->thresholds,
                            area_uniform(report));
    },
    [](const MeasureReport& r) { return r.tnt ? tnt_lines(*r.tnt) : std::string(); },
    [](const MeasureReport& r, nlohmann::json& json) {
      if (r.tnt) json["tanks_and_temples_protocol"] = tnt_json(*r.tnt);
    }};

const FigureFamily kImageBased = {
    "image-based",
    false,
    [](const MeasurePlan& plan, const Model&, const Model&) { return plan.image_based.has_value(); },
    [](FamilyInputs& in, MeasureReport& report) {
      in.stage = fmt::format("comparing {} and {} image by image (IBSM)", in.a.path(), in.b.path());
      in.progress.stage("image-based comparison");
      report.image_based =
          image_based_comparison(test_surface(in.a), test_surface(in.b), *in.plan.image_based);
    },
    [](const MeasureReport& r) { return r.image_based ? image_based_lines(*r.image_based) : std::string(); },
    [](const MeasureReport& r, nlohmann::json& json) {
      if (r.image_based) json["image_based"] = image_based_json(*r.image_based);
    }};

}  // namespace

const std::vector<FigureFamily>& figure_families() {
  static const std::vector<FigureFamily> families = {kReconstruction, kMpeg, kDtu, kTanksAndTemples,
                                                     kImageBased};
  return families;
}

std::string family_sections(const MeasureReport& report) {
  std::string out;
  for (const FigureFamily& family : figure_families()) out += family.text(report);
  return out;
}

void add_family_json(const MeasureReport& report, nlohmann::json& json) {
  for (const FigureFamily& family : figure_families()) family.json(report, json);
}

void merge_reconstruction(MeasureReport& report, const MeasurePlan& plan, const SampleFigures& a_to_b,
                          const SampleFigures& b_to_a) {
  report.reconstruction =
      reconstruction_figures(a_to_b, b_to_a, thresholds_of(plan, report.diagonal), area_uniform(report));
  certify_reconstruction(report);
}

}  // namespace roving
