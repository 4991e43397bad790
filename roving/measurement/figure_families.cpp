// The families of figures and their order (figure_families.h).
#include "figure_families.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <functional>

#include "roving/gl_methods/image_based_report.h"
#include "roving/mpeg/mpeg_report.h"
#include "roving/reconstruction/reconstruction_report.h"

namespace roving {
namespace {

using json = nlohmann::json;
using Format = std::function<std::string(double)>;

std::string plain(double x) { return fmt::format("{:.6g}", x); }
std::string percent(double share) { return fmt::format("{:.4g}%", 100 * share); }
std::string decibels(double x) { return fmt::format("{:.6g} dB", x); }

// A figure's text: a number, or an interval's estimate and its [lower, upper] (by `bounds`, else
// as the estimate); `none` for null.
std::string figure_text(const json& value, const Format& format, const char* none = "none",
                        const Format& bounds = {}) {
  if (value.is_number()) return format(value.get<double>());
  if (value.is_object() && value.contains("estimate") && value["estimate"].is_number()) {
    std::string text = format(value["estimate"].get<double>());
    if (value["lower"].is_number() && value["upper"].is_number()) {
      const Format& b = bounds ? bounds : format;
      text += fmt::format(" [{}, {}]", b(value["lower"].get<double>()), b(value["upper"].get<double>()));
    }
    return text;
  }
  return none;
}

// A figure and its interval given beside it (`interval`: {lower, upper}, or absent).
std::string with_interval(const json& value, const json& interval, const Format& format, const Format& bounds = {}) {
  if (!interval.is_object()) return figure_text(value, format);
  return figure_text({{"estimate", value}, {"lower", interval["lower"]}, {"upper", interval["upper"]}}, format,
                     "none", bounds);
}

// A length in model units and as a percentage of the report's diagonal, as the page shows each
// direction's.
Format length_of(const json& report) {
  const double diagonal = report.value("diagonal", 0.0);
  return [diagonal](double x) { return fmt::format("{:.6g} ({:.4g}%)", x, 100 * x / diagonal); };
}

FigureRows reconstruction_figures(const json& report) {
  const json& r = report["reconstruction"];
  const Format length = length_of(report);
  FigureRows rows = {
      {"accuracy: mean |d|, TEST to REF",
       with_interval(r["accuracy"]["mean"], r["accuracy"].value("mean_interval", json()), length, plain)},
      {"completeness: mean |d|, REF to TEST",
       with_interval(r["completeness"]["mean"], r["completeness"].value("mean_interval", json()), length, plain)},
      {"Chamfer distance (mean of the two)",
       with_interval(r["chamfer_mean"], r.value("chamfer_mean_interval", json()), length, plain)},
      {"Chamfer, squared (mean of the two)", figure_text(r["chamfer_squared_mean"], plain)},
      {"normal consistency", figure_text(r["normal_consistency"], plain, "none (the method names no faces)")}};
  for (const json& t : r["thresholds"]) {
    const std::string at = "at tau = " + length(t["tau"].get<double>());
    rows.push_back({"precision " + at, with_interval(t["precision"], t.value("precision_interval", json()), percent)});
    rows.push_back({"recall " + at, with_interval(t["recall"], t.value("recall_interval", json()), percent)});
    rows.push_back({"F-score " + at, with_interval(t["f_score"], t.value("f_score_interval", json()), percent)});
    for (const char* key : {"precision", "recall", "f_score"}) {
      const std::string certified = std::string(key) + "_certified";
      if (!t.contains(certified)) continue;
      rows.push_back({fmt::format("{} {}, certified", std::string(key) == "f_score" ? "F-score" : key, at),
                      fmt::format("[{}, {}]", percent(t[certified]["lower"].get<double>()),
                                  percent(t[certified]["upper"].get<double>()))});
    }
  }
  return rows;
}

// A PSNR: null where its error is 0.
std::string psnr_text(const json& value) { return figure_text(value, decibels, "infinite (no error)"); }

FigureRows mpeg_figures(const json& report) {
  const json& m = report["mpeg_pcc"];
  FigureRows rows = {{"geometry PSNR's peak", fmt::format("{} ({})", figure_text(m["peak"], plain),
                                                          m.value("peak_from", std::string()))}};
  const std::pair<const char*, const char*> directions[] = {
      {"symmetric", "(symmetric)"}, {"a_to_b", "A to B"}, {"b_to_a", "B to A"}};
  for (const auto& [key, label] : directions) {
    const json& d = m[key];
    for (const char* figure : {"d1_psnr", "d2_psnr", "y_psnr"}) {
      if (!d.contains(figure)) continue;
      std::string name = figure;
      name = name.substr(0, name.find('_'));
      for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      rows.push_back({fmt::format("{} PSNR {}", name, label), psnr_text(d[figure])});
    }
  }
  if (m.contains("exact_surface") && m["exact_surface"].is_object()) {
    const json& e = m["exact_surface"]["symmetric"];
    rows.push_back({"D1 PSNR of the surfaces (symmetric)",
                    with_interval(e["d1_psnr"], e.value("d1_psnr_interval", json()), decibels)});
    rows.push_back({"D2 PSNR of the surfaces (symmetric)",
                    with_interval(e["d2_psnr"], e.value("d2_psnr_interval", json()), decibels)});
  }
  return rows;
}

// A protocol's figure over its runs' seeds: mean, standard deviation, range.
std::string spread_text(const json& spread, const char* key, const Format& format) {
  const json& s = spread[key];
  return fmt::format("mean {}, sd {}, from {} to {}", format(s["mean"].get<double>()), format(s["sd"].get<double>()),
                     format(s["min"].get<double>()), format(s["max"].get<double>()));
}

FigureRows dtu_figures(const json& report) {
  const json& d = report["dtu_protocol"];
  const char* none = "none (no distance below max_dist)";
  FigureRows rows = {{"accuracy (mean_d2s)", figure_text(d["accuracy"], plain, none)},
                     {"completeness (mean_s2d)", figure_text(d["completeness"], plain, none)},
                     {"overall", figure_text(d["overall"], plain, none)}};
  if (d["spread"].is_object()) {
    rows.push_back({fmt::format("overall over {} seeds", d["runs"].size()), spread_text(d["spread"], "overall", plain)});
  }
  return rows;
}

FigureRows tanks_and_temples_figures(const json& report) {
  const json& t = report["tanks_and_temples_protocol"];
  FigureRows rows = {{"tau", figure_text(t["tau"], plain)},
                     {"precision", figure_text(t["precision"], percent)},
                     {"recall", figure_text(t["recall"], percent)},
                     {"F-score", figure_text(t["fscore"], percent)}};
  const json& registration = t["registration"];
  if (registration.is_object() && registration["spread"].is_object()) {
    rows.push_back({fmt::format("F-score over {} registrations", registration["runs"].size()),
                    spread_text(registration["spread"], "fscore", percent)});
  }
  return rows;
}

FigureRows image_based_figures(const json& report) {
  const json& ib = report["image_based"];
  FigureRows rows = {{"depth PSNR", figure_text(ib["depth_psnr"], decibels, "none (no pixel both cover)")},
                     {"unmatched pixels", figure_text(ib["unmatched_percent"], [](double x) {
                        return fmt::format("{:.4g}%", x);
                      })}};
  if (ib.contains("colour") && ib["colour"].is_object()) {
    rows.push_back({"colour: PSNR R'G'B'", psnr_text(ib["colour"]["psnr_rgb"])});
    rows.push_back({"colour: PSNR Y'CbCr 6:1:1", psnr_text(ib["colour"]["psnr_ycbcr_611"])});
  }
  return rows;
}

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
    "Reconstruction figures",
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
    },
    {{"chamfer_mean", "/reconstruction/chamfer_mean"},
     {"normal_consistency", "/reconstruction/normal_consistency"},
     {"tau", "/reconstruction/thresholds/0/tau"},
     {"precision", "/reconstruction/thresholds/0/precision"},
     {"recall", "/reconstruction/thresholds/0/recall"},
     {"f_score", "/reconstruction/thresholds/0/f_score"}},
    reconstruction_figures};

// MPEG's figures beside the distances: of two point clouds always, of anything with --pcc (two
// meshes: also D1 and D2 of the surfaces themselves, from the directions' closest points).
const FigureFamily kMpeg = {
    "mpeg",
    "MPEG's point-cloud figures",
    "mpeg_pcc",
    false,
    [](const MeasurePlan& plan, const Model& a, const Model& b) {
      return (a.type == ModelType::Points && b.type == ModelType::Points) || plan.pcc_only;
    },
    [](FamilyInputs& in, MeasureReport& report) {
      in.stage = fmt::format("computing MPEG's point-cloud figures of {} and {}", in.a.path(), in.b.path());
      in.progress.stage("MPEG point-cloud figures");
      report.mpeg = mpeg_report(in.a, in.b, in.plan);
      in.warn(report.mpeg->warnings);
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
    },
    {{"mpeg_d1_psnr", "/mpeg_pcc/symmetric/d1_psnr"},
     {"mpeg_d2_psnr", "/mpeg_pcc/symmetric/d2_psnr"},
     {"mpeg_y_psnr", "/mpeg_pcc/symmetric/y_psnr"}},
    mpeg_figures};

// DTU's evaluation; with --symmetric, the exact figures where it measures too.
const FigureFamily kDtu = {
    "dtu",
    "The DTU protocol",
    "dtu_protocol",
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
    },
    {{"dtu_accuracy", "/dtu_protocol/accuracy"},
     {"dtu_completeness", "/dtu_protocol/completeness"},
     {"dtu_overall", "/dtu_protocol/overall"}},
    dtu_figures};

// Tanks and Temples' evaluation, after run.py's registration where a trajectory was given; with
// --symmetric, the exact figures within the crop too.
const FigureFamily kTanksAndTemples = {
    "tanks-and-temples",
    "The Tanks and Temples protocol",
    "tanks_and_temples_protocol",
    true,
    [](const MeasurePlan& plan, const Model&, const Model&) { return plan.tnt.has_value(); },
    [](FamilyInputs& in, MeasureReport& report) {
      ProtocolInputs& protocol = *in.protocol;
      in.stage = fmt::format("running the Tanks and Temples protocol on {} (ground truth) and {}",
                             in.a.path(), in.b.path());
      in.progress.stage("Tanks and Temples protocol");
      for (const Model* model : {&in.a, &in.b}) {
        if (model->non_finite_dropped == 0) continue;
        in.warn({fmt::format("{}: {} points with a NaN or infinite coordinate left out, as the Tanks and Temples "
                             "toolbox's crop leaves them out",
                             model->path(), model->non_finite_dropped)});
      }
      report.tnt = tanks_and_temples_report(in.a, in.b, *in.plan.tnt, *protocol.tnt, in.progress.callback());
      in.progress.clear();
      if (!protocol.tnt_registrations.empty()) {
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
    },
    {{"tnt_tau", "/tanks_and_temples_protocol/tau"},
     {"tnt_precision", "/tanks_and_temples_protocol/precision"},
     {"tnt_recall", "/tanks_and_temples_protocol/recall"},
     {"tnt_f_score", "/tanks_and_temples_protocol/fscore"}},
    tanks_and_temples_figures};

const FigureFamily kImageBased = {
    "image-based",
    "The image-based comparison (IBSM)",
    "image_based",
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
    },
    {{"ibsm_psnr_rgb", "/image_based/colour/psnr_rgb"},
     {"ibsm_psnr_ycbcr_611", "/image_based/colour/psnr_ycbcr_611"},
     {"ibsm_depth_psnr", "/image_based/depth_psnr"},
     {"ibsm_unmatched_percent", "/image_based/unmatched_percent"}},
    image_based_figures};

}  // namespace

const std::vector<FigureFamily>& figure_families() {
  static const std::vector<FigureFamily> families = {kReconstruction, kMpeg, kDtu, kTanksAndTemples,
                                                     kImageBased};
  return families;
}

std::vector<const FigureFamily*> summary_families() {
  std::vector<const FigureFamily*> families;
  for (const char* name : {"image-based", "mpeg", "reconstruction", "dtu", "tanks-and-temples"}) {
    for (const FigureFamily& family : figure_families()) {
      if (family.name == std::string(name)) families.push_back(&family);
    }
  }
  for (const FigureFamily& family : figure_families()) {  // a family added since
    if (std::find(families.begin(), families.end(), &family) == families.end()) families.push_back(&family);
  }
  return families;
}

std::string summary_cell(const nlohmann::json& report, const SummaryColumn& column) {
  const nlohmann::json::json_pointer pointer(column.pointer);
  if (!report.contains(pointer)) return "";
  const nlohmann::json& value = report[pointer];
  const nlohmann::json& number = value.is_object() && value.contains("estimate") ? value["estimate"] : value;
  return number.is_number() ? fmt::format("{}", number.get<double>()) : std::string();
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
