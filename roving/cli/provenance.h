// What a report needs to be reproduced: the tool's version and commit, and the command line.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace roving {

// "roving 0.1.0 (commit 924789a1b2c3)": the version and the commit this binary was built from.
std::string version_line();

// {"name": "roving", "version": ..., "commit": ...}
nlohmann::json tool_json();

// argv joined by spaces, each argument quoted for a POSIX shell where it needs it.
std::string command_line(int argc, char** argv);

}  // namespace roving
