// roving-bench's throughput table: each exact method (Embree and CGAL deciding by the shared
// rule, every semantics) against the raw limit of its own library on the same samples
// (roving/core/raw_queries.h), with the samples in their own order and stored sorted along a
// Z-order curve (coherent queries). Answers are checked before anything is timed: the order must
// change no answer, and the raw
// query must agree with the exact one wherever the rule's tolerance does not decide.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "report_table.h"
#include "roving/core/sample_set.h"

namespace roving {

struct ThroughputPair {
  std::string name;
  TriangleMesh test;
  SampleSet samples;
  double max_error;
};

struct ThroughputStudy {
  ReportTable table;
  std::vector<std::string> failures;  // checks that did not hold
};

// Each timing is the median of `repeats` runs, ours and raw interleaved. `step` hears of each pair.
ThroughputStudy exact_throughput(const std::vector<ThroughputPair>& pairs, int repeats,
                                 const std::function<void(const std::string&)>& step);

}  // namespace roving
