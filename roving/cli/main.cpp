// `roving`: measure the shape dissimilarity of a test model M_C from a reference model M_R.
#include <cstdio>
#include <new>

#include "command_line.h"
#include "provenance.h"
#include "roving/core/memory_budget.h"
#include "roving/formats/files/atomic_file.h"
#include "roving/formats/files/file_bytes.h"
#include "roving/formats/meshes/mtl_reader.h"

int main(int argc, char** argv) {
  const std::unique_ptr<roving::CommandLine> made = roving::make_command_line();
  roving::CommandLine& line = *made;
  const CLI::App* measure = line.measure;
  const CLI::App* batch = line.batch;
  const CLI::App* merge = line.merge;
  line.args.command_line = line.batch_args.defaults.command_line = line.merge_args.command_line =
      roving::command_line(argc, argv);
  std::string error;
  try {
    error = roving::parse_command_line(line, std::vector<std::string>(argv + 1, argv + argc));
    if (error.empty() && line.version) {
      std::printf("%s\n", roving::version_line().c_str());
      return 0;
    }
    if (error.empty() && !measure->parsed() && !batch->parsed() && !merge->parsed())
      error = "a subcommand (measure, batch or merge) is required";
  } catch (const CLI::CallForHelp& e) {
    return line.app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return line.app.exit(e);
  }
  if (!error.empty()) {
    const bool subcommand =
        argc > 1 && (std::string(argv[1]) == "measure" || std::string(argv[1]) == "batch" ||
                     std::string(argv[1]) == "merge");
    std::fprintf(stderr, "roving: error: %s (see roving %s--help)\n", error.c_str(),
                 subcommand ? (std::string(argv[1]) + " ").c_str() : "");
    return 2;
  }
  roving::references_may_leave_folder(line.trust_references);
  roving::require_materials(line.strict_materials);
  roving::remove_temporaries_on_signals();  // SIGINT, SIGTERM: no temporary file left, exit 130 / 143
  std::string stage = "starting";           // what the run is doing, for the message when memory runs out
  try {
    if (merge->parsed()) return roving::run_merge(line.merge_args, stage);
    return batch->parsed() ? roving::run_batch(line.batch_args, stage)
                           : roving::run_measure(line.args, stage);
  } catch (const roving::UsageError& e) {
    std::fprintf(stderr, "roving: error: %s (see roving %s --help)\n", e.what(),
                 batch->parsed() ? "batch" : merge->parsed() ? "merge" : "measure");
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "roving: error: out of memory while %s (available: %.3g GiB)\n", stage.c_str(),
                 roving::available_memory() / (1024.0 * 1024 * 1024));
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roving: error: %s\n", e.what());
    return 1;
  }
}
