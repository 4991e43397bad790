// The image-based comparison (IBSM) as reports show it, with mmetric's names for its figures: its
// text section and docs/report-json.md's `image_based`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "roving/gl_methods/image_based.h"

namespace roving {

std::string image_based_lines(const ImageBasedResult& result);
nlohmann::json image_based_json(const ImageBasedResult& result);

}  // namespace roving
