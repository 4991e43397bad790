// One pair measured across processes: `roving measure ... --shard I/N --shard-out PART` writes the
// I-th slice of each direction's samples as a part (what the figures are rebuilt from: each
// sample's d, hit and weight, 17 bytes, with --symmetric also |n . n'| at its correspondence, and
// the models' description), and `roving merge PART...` rebuilds the report one process gives. The
// statistics, percentiles, histogram, confidence intervals, two-sided summary and reconstruction
// figures come from the very arrays one process holds, in its order, so they are equal bit for bit; the
// certified Hausdorff interval is each shard's share of the reference's triangles, merged as the
// largest lower and upper ends: it holds the true value within the same width, with ends that may
// differ from one process's within that width. Times are summed over the shards.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "measure.h"

namespace roving {

// Writes `run`, a shard's (run.report.shard set), as a part: a first line naming the format, one
// line of JSON (what was measured, by which tool and arguments, the models, the slices), then per
// direction d (float64), hit (uint8), weight (float64) and, where the faces are known, |n . n'|
// (float64) per sample, little-endian.
void write_shard_part(std::FILE* out, const MeasureArguments& args, const MeasureRun& run);

struct MergeArguments {
  std::vector<std::string> parts;
  std::string json_path;  // as measure's --json: a file, or - for stdout
  bool quiet = false;
  std::string command_line;
};

// The merged report and the plan the shards' arguments make (its gates), with the header text the
// shards printed.
struct MergedReport {
  MeasurePlan plan;
  MeasureReport report;
  std::string header;
};

// Reads the parts and rebuilds the report; throws roving::Error naming the part and what is wrong
// (not a part, truncated, another pair or other options, a shard missing or given twice).
MergedReport merge_parts(const std::vector<std::string>& parts, const std::string& command_line);

// `roving merge`: the merged report as text on stdout (or JSON with --json), the shards' gates
// applied; returns the exit code as run_measure does.
int run_merge(const MergeArguments& args, std::string& stage);

}  // namespace roving
