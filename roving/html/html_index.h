// An index page of many measurements (a batch, the benchmark's results): one sortable table
// row per measurement, each linking to its own page. Self-contained like the pages it links.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace roving {

struct HtmlTable {
  std::string title, intro;  // intro: HTML, shown above the table
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // cells as text; numbers sort as numbers
  std::vector<std::string> links;              // per row: its page (relative), or empty
  std::vector<bool> failed;                    // per row: shown highlighted
};

struct HtmlIndex {
  std::string title, intro;  // intro: HTML
  std::vector<HtmlTable> tables;
};

void write_html_index(std::FILE* out, const HtmlIndex& index);

}  // namespace roving
