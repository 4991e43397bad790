// `--html`: a measurement's report as one self-contained web page (roving/html), and a batch's
// index of such pages.
#pragma once

#include <string>

#include "roving/measurement/measure_report.h"
#include "roving/html/html_page.h"

namespace roving {

// The page of `report` (each direction's heat map on its reference, its figures and histogram),
// with `text` (the terminal's report) and `json` (the JSON report) embedded.
HtmlPage measurement_page(const MeasureReport& report, const std::string& text, const nlohmann::json& json);

}  // namespace roving
