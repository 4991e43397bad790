// Warnings about a measurement that is probably not what the user meant: models in different
// frames, an inside-out reference, too many samples without a hit. One line each, for stderr
// and the JSON report.
#pragma once

#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/core/statistics.h"
#include "roving/representations/model.h"

namespace roving {

// Before measuring: the two models' boxes disjoint, or the reference's reaching farther than h
// out of the test's (offset, scaled or turned frames).
std::vector<std::string> alignment_warnings(const Model& a, const Model& b, double max_error);

// A closed reference whose signed volume is negative (inside out).
std::vector<std::string> orientation_warnings(const Model& reference);

// After measuring: more than 5% of the samples without a hit.
std::vector<std::string> result_warnings(const Statistics& statistics, Semantics semantics);

// Both models have colour but `method` found no colour at its hits.
std::string no_colour_warning(const std::string& method);

}  // namespace roving
