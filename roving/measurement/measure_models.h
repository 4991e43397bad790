// Measuring a loaded pair: each direction's samples against the other model, then the families of
// figures the plan asks for (figure_families.h), into a MeasureReport.
#pragma once

#include <optional>
#include <string>

#include "measure_plan.h"
#include "measure_report.h"
#include "progress.h"
#include "roving/streaming/streamed_measurement.h"
#include "roving/representations/model.h"

namespace roving {

struct ProtocolInputs;  // figure_families.h

// A model read for `plan`: as load_model reads it, or, with --pcc, a point cloud as its file has it
// (no surfels, no normals estimated). With a protocol alone, a point cloud as its file has it too,
// and a binary PLY mesh whose points the protocol takes as its vertices (Tanks and Temples' both
// models, DTU's reference: `reference` says which this is) read as its vertices alone
// (Model::mesh_vertices_only): a 10 M-triangle mesh's faces are 120 MB not read.
Model load_for(const MeasurePlan& plan, const std::string& path, std::optional<ModelType> type, bool reference);

// MPEG's point-cloud figures: of two point clouds as pc_error computes them (its D2 takes A's
// normals from its file; estimated ones are not pc_error's), or, where a model is a mesh, as
// mmetric's compare --mode pcc does, each mesh sampled as mmetric samples it; with the plan's
// peak, normals file and pc_error's (or mmetric's) options.
MpegReport mpeg_report(const Model& a, const Model& b, const MeasurePlan& plan);

// --pcc where a model is a point cloud: MPEG's figures of a and b alone (report.pcc_only; a mesh
// among them sampled as mmetric samples it); throws naming a model that is neither a point cloud
// nor a mesh.
void measure_point_clouds(const Model& a, const Model& b, const MeasurePlan& plan, MeasureReport& report,
                          Progress& progress, std::string& stage, const WarnFn& warn);

// Fills the report's method, semantics, diagonal and h for the loaded pair; throws on a pair the
// plan cannot measure (a point-cloud test, h beyond both models).
void describe_pair(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report);

// After describe_pair, measures: a's samples against b (and b's against a when symmetric), filling
// `report` but for its provenance and load times; warnings go to `warn` as found. `samples_of_a`,
// when given, are a's samples already made (a batch reuses them across pairs). `releasable_a`,
// when given, is `a` itself, whose geometry nothing reads once it is sampled: it gives it up
// then, so that the query runs without it. `streamed_a`, when given, is a's file read a block of
// faces at a time (with its vertex sums where its vertices are the samples), `a` its summary
// (streamed_model).
void measure_models(const Model& a, const Model& b, MeasurePlan& plan, MeasureReport& report,
                    Progress& progress, std::string& stage, const WarnFn& warn, const SampleSet* samples_of_a,
                    Model* releasable_a = nullptr, ReferenceStream* streamed_a = nullptr,
                    ProtocolInputs* protocol = nullptr);
}  // namespace roving
