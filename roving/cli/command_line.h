// The options of `roving measure` and `roving batch`, declared once: the tool parses its argv with
// them, and the Python module parses its keyword arguments with the same declarations, so both
// take the same names, defaults and checks and give the same one-line errors.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "batch.h"
#include "measure.h"
#include "merge.h"

namespace roving {

struct CommandLine {
  CLI::App app;
  CLI::App* measure = nullptr;
  CLI::App* batch = nullptr;
  CLI::App* merge = nullptr;
  MeasureArguments args;      // measure's
  BatchArguments batch_args;  // batch's
  MergeArguments merge_args;  // merge's
  bool trust_references = false;
  bool strict_materials = false;
  bool version = false;
};

// The whole command line, its options bound to the returned object's members (so it stays where
// it was made).
std::unique_ptr<CommandLine> make_command_line();

// Parses `arguments` (argv without the program's name); for measure, fills args.figure_arguments. Returns the one-line message of a parse
// error, naming the first unknown subcommand or option with the nearest known one ("did you
// mean"), or CLI11's own message; empty on success. Lets CLI::CallForHelp and
// CLI::CallForAllHelp through.
std::string parse_command_line(CommandLine& line, std::vector<std::string> arguments);

// The nearest of `candidates` to `given` within a few edits, or empty.
std::string nearest_name(const std::string& given, const std::vector<std::string>& candidates);

}  // namespace roving
