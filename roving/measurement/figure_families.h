// The families of figures a measurement computes from a measured pair beyond each direction's
// distance statistics: the reconstruction figures, MPEG's, a benchmark's protocol (DTU's, Tanks and
// Temples'), the image-based comparison. Each says whether a plan asks for it, computes its figures
// into the report from what the directions measured (their samples and per-sample results) and the
// models, and writes its own text and JSON sections; the reconstruction figures also merge from
// shards' parts. measure_models runs the families a plan asks for, in this list's order, and the
// reports write their sections in the same order. A new family is a folder of its own (its figures
// and their sections) and one entry here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "measure_models.h"

namespace roving {

// What a protocol reads before the models (a wrong file fails before a model is read), and run.py's
// registration, run on the models as loaded, before TEST is aligned.
struct ProtocolInputs {
  std::optional<DtuFiles> dtu;
  std::optional<TanksAndTemplesFiles> tnt;
  std::vector<TanksAndTemplesRegistrationRun> tnt_registrations;
  double tnt_registration_seconds = 0;
};

// What a family computes from: the pair (as measured: a's samples against b, and b's against a
// with --symmetric, in report.directions), the plan, and where it says what it is doing.
struct FamilyInputs {
  const Model& a;
  const Model& b;
  const MeasurePlan& plan;
  ProtocolInputs* protocol;  // null where no protocol was asked for
  Progress& progress;
  std::string& stage;
  const WarnFn& warn;
};

// One of a family's figures as the batch's summary.csv holds it (and its index page shows it):
// its column, and where a JSON report holds it (a JSON pointer; an interval's object gives its
// estimate).
struct SummaryColumn {
  const char* name;
  const char* pointer;
};

// The web page's rows of a family's figures: label and value as text.
using FigureRows = std::vector<std::pair<std::string, std::string>>;

struct FigureFamily {
  const char* name;
  const char* title;    // its heading on the web page
  const char* section;  // its key in the JSON report
  // A benchmark's protocol: with --protocol alone (no --symmetric), the only family run.
  bool protocol;
  bool (*asked)(const MeasurePlan& plan, const Model& a, const Model& b);
  void (*compute)(FamilyInputs& inputs, MeasureReport& report);
  // Its sections where the report holds its figures: the text's (empty where it holds none) and
  // the JSON report's (added to `json`).
  std::string (*text)(const MeasureReport& report);
  void (*json)(const MeasureReport& report, nlohmann::json& json);
  // Its columns in the batch's summary.csv, and its figures on the web page, both from a JSON
  // report holding its section.
  std::vector<SummaryColumn> summary;
  FigureRows (*page_figures)(const nlohmann::json& report);
};

const std::vector<FigureFamily>& figure_families();

// The families in summary.csv's column order: the order its columns have always had (IBSM, MPEG's,
// the reconstruction figures, DTU's, Tanks and Temples'); a new family's columns come last.
std::vector<const FigureFamily*> summary_families();

// A summary.csv cell: the number at `column.pointer` in a report's JSON ("{}", the shortest
// text that reads back the same double), an interval's estimate; empty where there is none.
std::string summary_cell(const nlohmann::json& report, const SummaryColumn& column);

// The families' text sections, in order, of those whose figures the report holds.
std::string family_sections(const MeasureReport& report);

// Their JSON sections, added to `json`.
void add_family_json(const MeasureReport& report, nlohmann::json& json);

// The reconstruction figures of a merge: from the shards' arrays as measure_models computes them
// from a run's (merge.h), with their certified bounds where the parts carried them.
void merge_reconstruction(MeasureReport& report, const MeasurePlan& plan, const SampleFigures& a_to_b,
                          const SampleFigures& b_to_a);

}  // namespace roving
