// Every distance method by name, for the CLI, the benchmark and the cross-checking tests.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "roving/distance_method.h"

namespace roving {

// Names accepted by make_method (the CLI's --method).
std::vector<std::string> method_names();

// Throws roving::Error naming `--method`, listing the known names, for an unknown one.
std::unique_ptr<DistanceMethod> make_method(const std::string& name);

}  // namespace roving
