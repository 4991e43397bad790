// Provenance of a report: version, commit, command line.
#include "provenance.h"

#include <fmt/format.h>

#include "version.h"

namespace roving {

std::string version_line() { return fmt::format("roving {} (commit {})", ROVING_VERSION, ROVING_COMMIT); }

nlohmann::json tool_json() { return {{"name", "roving"}, {"version", ROVING_VERSION}, {"commit", ROVING_COMMIT}}; }

std::string command_line(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    const std::string argument = argv[i];
    const bool plain = !argument.empty() && argument.find_first_not_of(
                                                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                "0123456789-_./:=%+,@") == std::string::npos;
    if (i) line += ' ';
    if (plain) {
      line += argument;
    } else {
      line += '\'';
      for (char c : argument) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
      line += '\'';
    }
  }
  return line;
}

}  // namespace roving
