// The reconstruction figures as reports show them: their JSON section (docs/report-json.md's
// `reconstruction`; a protocol's exact figures in the same form) and their text table.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "roving/reconstruction/reconstruction_figures.h"

namespace roving {

// An estimate as `json[key]`, a number whatever the samples, and its 95% interval where it has one
// beside it as `json[key + "_interval"]` ({lower, upper}), as every interval of the report is given.
void add_estimate(nlohmann::json& json, const std::string& key, const Estimate& estimate);
// An estimate as text: "value" or "value [lower, upper]" (8 and 6 significant digits).
std::string estimate_text(const Estimate& estimate);

nlohmann::json reconstruction_json(const ReconstructionFigures& figures);

// The table: each length in model units and over `diagonal`, then precision, recall and F-score at
// each threshold with their intervals and certified bounds where they exist.
std::string reconstruction_lines(const ReconstructionFigures& figures, double diagonal);

}  // namespace roving
