// Markdown and CSV rendering of report tables.
#include "report_table.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "roving/core/error.h"

namespace roving {

std::string figure(double value, int digits) {
  return std::isnan(value) ? "N/A" : fmt::format("{:.{}f}", value, digits);
}

std::string ReportTable::markdown() const {
  std::string out = "| " + fmt::format("{}", fmt::join(header, " | ")) + " |\n|";
  for (std::size_t i = 0; i < header.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : rows) out += "| " + fmt::format("{}", fmt::join(row, " | ")) + " |\n";
  return out;
}

void ReportTable::write_csv(const std::string& path) const {
  std::ofstream file(path);
  if (!file) throw Error(fmt::format("{}: cannot open for writing", path));
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const bool quote = cells[i].find_first_of(",\"\n") != std::string::npos;
      std::string cell = cells[i];
      for (std::size_t at = 0; quote && (at = cell.find('"', at)) != std::string::npos; at += 2)
        cell.insert(at, "\"");
      file << (i ? "," : "") << (quote ? "\"" + cell + "\"" : cell);
    }
    file << "\n";
  };
  line(header);
  for (const auto& row : rows) line(row);
}

}  // namespace roving
