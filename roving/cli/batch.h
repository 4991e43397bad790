// `roving batch`: many pairs in one run. Each pair gets one JSON report (the `measure --json`
// schema plus a `batch` object) in the output folder, named by its place in the list and a key
// of its inputs' sha256 and its options, so an interrupted run resumes (and recomputes a pair
// whose files or options changed) and shards of one list never collide; then a merged CSV
// summary. A failing pair is recorded with its error and the others go on.
#pragma once

#include <string>
#include <vector>

#include "measure.h"
#include "roving/measurement/progress.h"

namespace roving {

// Exit code when the batch ran but some pair failed.
constexpr int kSomePairsFailedExitCode = 4;

struct BatchArguments {
  // A manifest (.csv with a header naming `reference`, `test` and optional per-pair columns
  // method, semantics, samples, seed, max_error, views, resolution, backend, camera_geometry,
  // view_culling, a protocol's; or .jsonl with those keys), or two folders whose files are paired
  // by name.
  std::vector<std::string> inputs;
  std::string out = "batch-results";
  std::string shard;  // "I/N": the I-th (0-based) of N contiguous slices of the pairs
  bool merge_only = false;
  bool html = false;           // a page per pair and index.html
  bool skip_unpaired = false;  // folder mode: measure the pairs found even if some files have no partner
  MeasureArguments defaults;  // options for every pair, overridden by the manifest's columns
};

// Measures every pair (or the shard's) into args.out; returns the exit code. `listener` hears the
// progress (the Python module's callback and Ctrl-C); where it throws, the batch stops there and
// rethrows, the pairs done kept and the one under way leaving nothing.
int run_batch(const BatchArguments& args, std::string& stage, const Progress::Listener& listener = {});

}  // namespace roving
