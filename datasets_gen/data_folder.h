// Where the development tools (roving-datasets, the benchmarks, the tests) find the real models.
#pragma once

#include <cstdlib>
#include <string>

namespace roving {

// $ROVING_DATA when set, else the checkout's data/ (ROVING_DATA_DIR, set by CMake), so a clone in
// any folder finds its models with nothing beside it.
inline std::string default_data_folder() {
  if (const char* env = std::getenv("ROVING_DATA"); env && *env) return env;
  return ROVING_DATA_DIR;
}

}  // namespace roving
