// Index pages: a static table, sorted by a click on its header (numbers as numbers).
#include "roving/html/html_index.h"

#include <fmt/format.h>

#include "roving/html/html_assets.h"
#include "roving/html/html_page.h"

namespace roving {
namespace {

constexpr const char* kSortScript = R"js(
'use strict';
document.querySelectorAll('table.sortable th').forEach(function (th, column) {
  th.addEventListener('click', function () {
    const body = th.closest('table').tBodies[0];
    const ascending = th.dataset.order !== 'ascending';
    th.closest('tr').querySelectorAll('th').forEach(function (other) { delete other.dataset.order; });
    th.dataset.order = ascending ? 'ascending' : 'descending';
    const key = function (row) { const text = row.cells[column].textContent; const x = parseFloat(text); return isNaN(x) ? text : x; };
    const rows = Array.from(body.rows).sort(function (a, b) {
      const x = key(a), y = key(b);
      const order = typeof x === typeof y ? (x < y ? -1 : x > y ? 1 : 0) : (typeof x === 'number' ? -1 : 1);
      return ascending ? order : -order;
    });
    rows.forEach(function (row) { body.appendChild(row); });
  });
});
document.body.dataset.ready = 'true';
)js";

constexpr const char* kIndexStyle = R"css(
#panel { max-width: none; }
table.sortable th { cursor: pointer; white-space: nowrap; border-bottom: 1px solid #888; }
table.sortable th[data-order=ascending]::after { content: " \25B2"; }
table.sortable th[data-order=descending]::after { content: " \25BC"; }
table.sortable tr.failed td { background: #fde0dd; }
table.sortable td { border-bottom: 1px solid #eee; }
)css";

}  // namespace

void write_html_index(std::FILE* out, const HtmlIndex& index) {
  fmt::print(out,
             "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
             "<meta name=\"generator\" content=\"surface roving\">\n<title>{}</title>\n<style>\n{}{}</style>\n"
             "</head>\n<body>\n<div id=\"panel\">\n<h1>{}</h1>\n{}\n",
             escape_html(index.title), html_assets::page_css, kIndexStyle, escape_html(index.title), index.intro);
  for (const HtmlTable& table : index.tables) {
    if (!table.title.empty()) fmt::print(out, "<h2>{}</h2>\n", escape_html(table.title));
    const bool links = !table.links.empty();
    fmt::print(out, "{}\n<table class=\"sortable\">\n<thead><tr>", table.intro);
    for (const std::string& name : table.header) fmt::print(out, "<th>{}</th>", escape_html(name));
    fmt::print(out, "{}</tr></thead>\n<tbody>\n", links ? "<th>page</th>" : "");
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
      const bool failed = r < table.failed.size() && table.failed[r];
      fmt::print(out, "<tr{}>", failed ? " class=\"failed\"" : "");
      for (const std::string& cell : table.rows[r]) fmt::print(out, "<td>{}</td>", escape_html(cell));
      const std::string link = r < table.links.size() ? table.links[r] : "";
      if (links) {
        fmt::print(out, "<td>{}</td>", link.empty() ? "" : fmt::format("<a href=\"{}\">view</a>", escape_html(link)));
      }
      fmt::print(out, "</tr>\n");
    }
    fmt::print(out, "</tbody>\n</table>\n");
  }
  fmt::print(out, "</div>\n<script>{}</script>\n</body>\n</html>\n", kSortScript);
}

}  // namespace roving
