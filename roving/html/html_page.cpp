// The measurement page: static HTML for the report, a JSON block with the surfaces as base64
// binary, and the embedded scripts that draw them.
#include "roving/html/html_page.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <algorithm>
#include <cmath>

#include "roving/html/html_assets.h"

namespace roving {
namespace {

template <typename T>
std::string base64(const std::vector<T>& values) {
  if (values.empty()) return "";
  const std::size_t bytes = values.size() * sizeof(T);
  std::string out(4 * ((bytes + 2) / 3) + 1, '\0');
  const int written =
      EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                      reinterpret_cast<const unsigned char*>(values.data()), static_cast<int>(bytes));
  out.resize(static_cast<std::size_t>(written));
  return out;
}

// JSON inside <script>: "</" would end the element early.
std::string script_json(const nlohmann::json& json) {
  std::string text = json.dump();
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.insert(at + 1, "\\");
  return text;
}

std::string css_colour(const std::array<unsigned char, 3>& c) {
  return fmt::format("rgb({},{},{})", c[0], c[1], c[2]);
}

// The colour map as a CSS gradient, from -range (left) to +range.
std::string colour_bar_gradient() {
  std::string stops;
  for (int i = 0; i <= 20; ++i) {
    stops += fmt::format(",{} {}%", css_colour(diverging_colour(i / 10.0 - 1)), i * 5);
  }
  return "linear-gradient(to right" + stops + ")";
}

std::string thousands(std::size_t n) {
  std::string digits = std::to_string(n);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3)
    digits.insert(static_cast<std::size_t>(at), ",");
  return digits;
}

// The histogram of signed d over the hits, each bar in the colour map's colour at its centre and
// outlined in grey: bars near d = 0 are near white, the page's background.
std::string histogram_svg(const Histogram& h, double range) {
  if (h.counts.empty() || !(h.high > h.low)) return "";
  const double width = 360, height = 120, left = 8, bottom = height + 4;
  const std::size_t tallest = std::max<std::size_t>(1, *std::max_element(h.counts.begin(), h.counts.end()));
  const double bar = width / h.counts.size();
  std::string svg = fmt::format(R"(<svg class="histogram" width="{}" height="{}" role="img">)",
                                width + 2 * left, height + 54);
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    const double centre = h.low + (i + 0.5) * (h.high - h.low) / h.counts.size();
    const double tall = height * h.counts[i] / tallest;
    svg += fmt::format(
        R"(<rect x="{:.2f}" y="{:.2f}" width="{:.2f}" height="{:.2f}" fill="{}" stroke="#777" stroke-width="0.5">)"
        R"(<title>{}</title></rect>)",
        left + i * bar, bottom - tall, std::max(bar - 0.5, 0.5), tall,
        css_colour(diverging_colour(range > 0 ? centre / range : 0)),
        fmt::format("d near {:.4g}: {} samples", centre, h.counts[i]));
  }
  svg +=
      fmt::format(R"(<line x1="{0}" x2="{1}" y1="{2}" y2="{2}" stroke="#888"/>)", left, left + width, bottom);
  svg += fmt::format(R"(<text x="{}" y="{}">{:.4g}</text>)", left, bottom + 16, h.low);
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">0</text>)",
                     left + width * (0 - h.low) / (h.high - h.low), bottom + 16);
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{:.4g}</text>)", left + width, bottom + 16,
                     h.high);
  svg += fmt::format(R"(<text x="{}" y="{}">signed d over the hits; tallest bar {} samples</text>)", left,
                     bottom + 32, tallest);
  if (h.below + h.above) {
    svg += fmt::format(R"(<text x="{}" y="{}">{} below and {} above this range</text>)", left, bottom + 46,
                       h.below, h.above);
  }
  return svg + "</svg>";
}

// The view's colour layers (HtmlView::Colours), each per element as `colours` is: delta E on the
// sequential map, REF's and TEST's own colours; null without colour.
nlohmann::json colours_json(const HtmlView& view) {
  if (!view.colours) return nullptr;
  const HtmlView::Colours& c = *view.colours;
  std::vector<unsigned char> delta_e, reference, test;
  for (float value : c.delta_e) {
    const auto colour = std::isnan(value)
                            ? kNoHitColour
                            : sequential_colour(c.delta_e_range > 0 ? value / c.delta_e_range : 0);
    delta_e.insert(delta_e.end(), colour.begin(), colour.end());
  }
  const auto bytes = [](const std::vector<float>& rgb, std::vector<unsigned char>& out) {
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
      const bool none = std::isnan(rgb[i]) || std::isnan(rgb[i + 1]) || std::isnan(rgb[i + 2]);
      for (int k = 0; k < 3; ++k) {
        out.push_back(none ? kNoHitColour[k]
                           : static_cast<unsigned char>(std::clamp(std::lround(rgb[i + k]), 0L, 255L)));
      }
    }
  };
  bytes(c.reference, reference);
  bytes(c.test, test);
  return {{"delta_e", base64(c.delta_e)},
          {"delta_e_colours", base64(delta_e)},
          {"delta_e_range", c.delta_e_range},
          {"reference", base64(reference)},
          {"test", base64(test)}};
}

// The sequential map as a CSS gradient, from 0 (left) to its top.
std::string sequential_bar_gradient() {
  std::string stops;
  for (int i = 0; i <= 10; ++i)
    stops += fmt::format(",{} {}%", css_colour(sequential_colour(i / 10.0)), i * 10);
  return "linear-gradient(to right" + stops + ")";
}

// `view`'s JSON; `shared`: the index of an earlier view with the same surface, whose positions and
// triangles it uses (-1: none), so that pages of one reference against many tests carry it once.
nlohmann::json view_json(const HtmlView& view, int shared) {
  const DisplaySurface& s = view.surface;
  std::vector<unsigned char> colours;
  colours.reserve(3 * s.values.size());
  for (float value : s.values) {
    const auto c =
        std::isnan(value) ? kNoHitColour : diverging_colour(view.range > 0 ? value / view.range : 0);
    colours.insert(colours.end(), c.begin(), c.end());
  }
  const char* element = s.element == HeatmapElement::Faces      ? "faces"
                        : s.element == HeatmapElement::Vertices ? "vertices"
                                                                : "points";
  const char* unit = s.element == HeatmapElement::Points ? "points" : "triangles";
  const std::size_t drawn = s.element == HeatmapElement::Points ? s.values.size() : s.triangles.size() / 3;
  const std::size_t source = s.element == HeatmapElement::Points ? s.source_elements : s.source_triangles;
  std::string decimated =
      fmt::format("All {} {} drawn; figures are over all {} samples.", thousands(drawn), unit,
                  thousands(view.positive + view.negative + view.zero + view.no_hit));
  if (drawn < source) {
    decimated = fmt::format(
        "Decimated for display to {} of {} {} (at most {} per page view){}. The figures are over all "
        "samples.",
        thousands(drawn), thousands(source), unit, thousands(kHtmlMaxTriangles),
        s.element == HeatmapElement::Points
            ? ": every few samples shown"
            : ": vertices merged on a grid, each merged element shows the mean d of "
              "what it merges");
  }
  // Where each element shows its own sample (face samples of a mesh without zero-area faces), the
  // page needs no table of which.
  bool identity = true;
  for (std::size_t e = 0; e < s.samples.size() && identity; ++e)
    identity = s.samples[e] == static_cast<std::int32_t>(e);
  return {
      {"label", view.label},
      {"element", element},
      {"geometry_of", shared},
      {"positions", shared < 0 ? base64(s.positions) : ""},
      {"triangles", shared < 0 ? base64(s.triangles) : ""},
      {"values", base64(s.values)},
      {"colours", base64(colours)},
      {"samples", identity ? "" : base64(s.samples)},
      {"resolution", base64(view.resolution)},
      {"method", view.method},
      {"range", view.range},
      {"diagonal", view.diagonal},
      {"max_error", view.max_error},
      {"point_size", s.point_size},
      {"signs",
       {{"positive", view.positive},
        {"negative", view.negative},
        {"zero", view.zero},
        {"no_hit", view.no_hit}}},
      {"decimated", decimated},
      {"pick_hint", std::string(s.values.size() > 300000 ? "Click" : "Hover over or click") +
                        " the surface for its sample's d. Drag to turn, scroll to zoom, right-drag to pan."},
      {"colours_of", colours_json(view)}};
}

// The report's provenance (its top-level tool, command_line and inputs; docs/report-json.md).
std::string provenance_html(const nlohmann::json& report) {
  // A field as text: strings as they are, anything else (numbers, null) as JSON writes it.
  const auto text = [](const nlohmann::json& field, const char* key) {
    if (!field.contains(key)) return std::string("?");
    return field[key].is_string() ? field[key].get<std::string>() : field[key].dump();
  };
  std::string rows;
  const auto row = [&](const std::string& name, const std::string& value) {
    rows += fmt::format("<tr><th>{}</th><td>{}</td></tr>", escape_html(name), escape_html(value));
  };
  if (report.contains("tool") && report["tool"].is_object()) {
    const nlohmann::json& tool = report["tool"];
    row("tool", fmt::format("{} {} (commit {})", text(tool, "name"), text(tool, "version"), text(tool, "commit")));
  }
  if (report.contains("command_line")) row("command line", text(report, "command_line"));
  if (report.contains("inputs") && report["inputs"].is_array()) {
    for (const nlohmann::json& input : report["inputs"]) {
      row(text(input, "role"), fmt::format("{} ({} bytes, sha256 {})", text(input, "path"), text(input, "bytes"),
                                           text(input, "sha256")));
    }
  }
  if (rows.empty()) return "";
  return "<details><summary>Provenance</summary><table>" + rows + "</table></details>";
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

void write_html_page(std::FILE* out, const HtmlPage& page) {
  fmt::print(out,
             "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
             "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
             "<meta name=\"generator\" content=\"surface "
             "roving\">\n<title>{}</title>\n<style>\n{}</style>\n</head>\n",
             escape_html(page.title), html_assets::page_css);
  fmt::print(
      out,
      "<body>\n<div id=\"app\">\n<main id=\"viewer\">\n<canvas id=\"view\"></canvas>\n<div id=\"legend\">\n"
      "<div id=\"shown\" hidden>show: <button type=\"button\" data-show=\"d\">d</button>"
      "<button type=\"button\" data-show=\"delta_e\">delta E</button>"
      "<button type=\"button\" data-show=\"reference\">REF's colour</button>"
      "<button type=\"button\" data-show=\"test\">TEST's colour</button></div>\n"
      "<div id=\"colourbar\" style=\"background: {0}\" data-d=\"{0}\" data-delta-e=\"{4}\"></div>\n"
      "<div id=\"bar-labels\"><span id=\"bar-low\"></span><span id=\"bar-middle\">0</span>"
      "<span id=\"bar-high\"></span></div>\n"
      "<div id=\"bar-units\"></div>\n"
      "<div id=\"swatches\"><span class=\"swatch\" style=\"background: {1}\"></span> no hit"
      "<span class=\"for-d\"> &nbsp; <span class=\"swatch\" style=\"background: {2}\"></span> TEST inside "
      "REF "
      "(d &lt; 0) &nbsp; <span class=\"swatch\" style=\"background: {3}\"></span> TEST outside (d &gt; "
      "0)</span>"
      "</div>\n"
      "<div id=\"decimated\"></div>\n</div>\n<div id=\"pick\"></div>\n</main>\n",
      colour_bar_gradient(), css_colour(kNoHitColour), css_colour(diverging_colour(-1)),
      css_colour(diverging_colour(1)), sequential_bar_gradient());
  fmt::print(out, "<aside id=\"panel\">\n<h1>{}</h1>\n", escape_html(page.title));
  if (page.views.size() > 1) {
    fmt::print(out, "<div id=\"directions\">");
    for (const HtmlView& view : page.views)
      fmt::print(out, "<button type=\"button\">{}</button>", escape_html(view.label));
    fmt::print(out, "</div>\n");
  }
  for (const HtmlView& view : page.views) {
    fmt::print(
        out,
        "<section class=\"direction\">\n<h2>{}</h2>\n<p class=\"subtitle\">{}</p>\n<table class=\"figures\">",
        escape_html(view.title), escape_html(view.subtitle));
    for (const auto& [name, value] : view.figures) {
      fmt::print(out, "<tr><th>{}</th><td class=\"number\">{}</td></tr>", escape_html(name),
                 escape_html(value));
    }
    fmt::print(out, "</table>\n{}\n</section>\n", histogram_svg(view.histogram, view.range));
  }
  for (const HtmlFigures& figures : page.pair_figures) {
    fmt::print(out, "<section class=\"pair\">\n<h2>{}</h2>\n<table class=\"figures\">", escape_html(figures.title));
    for (const auto& [name, value] : figures.rows) {
      fmt::print(out, "<tr><th>{}</th><td class=\"number\">{}</td></tr>", escape_html(name), escape_html(value));
    }
    fmt::print(out, "</table>\n</section>\n");
  }
  if (!page.warnings.empty()) {
    fmt::print(out, "<h2>Warnings</h2>\n<ul class=\"warnings\">");
    for (const std::string& line : page.warnings) fmt::print(out, "<li>{}</li>", escape_html(line));
    fmt::print(out, "</ul>\n");
  }
  fmt::print(out, "<details open><summary>Report</summary><pre>{}</pre></details>\n{}\n</aside>\n</div>\n",
             escape_html(page.report_text), provenance_html(page.report));
  nlohmann::json data = {{"views", nlohmann::json::array()}, {"shown_first", page.shown_first}};
  for (std::size_t i = 0; i < page.views.size(); ++i) {
    const DisplaySurface& s = page.views[i].surface;
    int shared = -1;
    for (std::size_t j = 0; j < i && shared < 0; ++j) {
      const DisplaySurface& other = page.views[j].surface;
      if (other.positions == s.positions && other.triangles == s.triangles) shared = static_cast<int>(j);
    }
    data["views"].push_back(view_json(page.views[i], shared));
  }
  fmt::print(out, "<script id=\"roving-data\" type=\"application/json\">{}</script>\n", script_json(data));
  fmt::print(out, "<script id=\"roving-report\" type=\"application/json\">{}</script>\n",
             script_json(page.report));
  fmt::print(out, "<script>{}</script>\n<script>{}</script>\n<script>{}</script>\n</body>\n</html>\n",
             html_assets::three_js, html_assets::orbit_controls_js, html_assets::page_js);
}

}  // namespace roving
