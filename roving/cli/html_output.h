// `--html`: a measurement's report as one self-contained web page (roving/html), and a batch's
// index of such pages.
#pragma once

#include <string>

#include "roving/formats/outputs/heatmap.h"
#include "roving/html/html_page.h"
#include "roving/measurement/measure_report.h"

namespace roving {

// The page of `report` (each direction's heat map on its reference, its figures and histogram; the
// pair's figures by family), with `text` (the terminal's report) and `json` (the JSON report)
// embedded; it opens on `shown` (--heatmap-of) where the models have colour.
HtmlPage measurement_page(const MeasureReport& report, const std::string& text, const nlohmann::json& json,
                          HeatmapQuantity shown = HeatmapQuantity::Distance);

}  // namespace roving
