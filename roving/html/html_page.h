// A measurement as one self-contained web page: the reference drawn in WebGL coloured by d
// (three.js inlined, the surface as base64 binary), orbit / zoom / pan, picking, the colour bar,
// and beside it the figures, histogram, warnings, text report and provenance. It opens from
// disk with no network and no server.
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roving/core/statistics.h"
#include "roving/html/display_surface.h"

namespace roving {

// The most triangles (or points) a page draws per view: about 30 MB of page per million.
constexpr std::size_t kHtmlMaxTriangles = 1000000;

// One direction's heat map and figures.
struct HtmlView {
  std::string label;  // the toggle's name ("A -> B"); empty for a single direction
  std::string title, subtitle;
  DisplaySurface surface;
  std::vector<std::uint8_t> resolution;  // per sample: a GL method's Resolution; empty for exact methods
  std::string method;
  double range = 0;      // the colour map's half-range, as the PNG and PLY heat maps use it
  double diagonal = 0;   // what % figures are of
  double max_error = 0;  // h
  std::size_t positive = 0, negative = 0, zero = 0, no_hit = 0;  // samples by the sign of d
  std::vector<std::pair<std::string, std::string>> figures;      // the table's rows: name, value
  Histogram histogram;
  // Where both models have colour: per element of `surface`, the CIEDE2000 delta E (NaN: a no-hit)
  // and REF's and TEST's colours (8-bit R'G'B', three per element; TEST's NaN where no hit, as
  // no_colour), which the page can show instead of d.
  struct Colours {
    std::vector<float> delta_e, reference, test;
    double delta_e_range = 0;  // the sequential map's top: the 99th percentile of delta E
  };
  std::optional<Colours> colours;
};

// A table of the pair's figures (both directions together, a family of figures'): its heading and
// rows of name and value.
struct HtmlFigures {
  std::string title;
  std::vector<std::pair<std::string, std::string>> rows;
};

struct HtmlPage {
  std::string title;
  std::vector<HtmlView> views;
  std::vector<HtmlFigures> pair_figures;  // beneath the directions', whichever is shown
  std::string shown_first = "d";          // the layer the page opens on: "d", or "delta_e" where there is colour
  std::vector<std::string> warnings;
  std::string report_text;  // the report as the terminal shows it
  nlohmann::json report;    // the JSON report (embedded whole; its provenance is shown)
};

// Writes the page. The caller keeps each view's surface within kHtmlMaxTriangles (display_surface()).
void write_html_page(std::FILE* out, const HtmlPage& page);

// Text made safe inside HTML elements and attribute values.
std::string escape_html(const std::string& text);

}  // namespace roving
