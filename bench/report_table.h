// Tables of the benchmark report, written as Markdown and CSV.
#pragma once

#include <string>
#include <vector>

namespace roving {

struct ReportTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string settings;  // one line above the table: what was measured, how

  std::string markdown() const;
  // Writes `path` (CSV, RFC 4180 quoting); throws roving::Error when it cannot.
  void write_csv(const std::string& path) const;
};

// Fixed-point text of a figure with `digits` decimals, or "N/A" for NaN.
std::string figure(double value, int digits = 4);

}  // namespace roving
