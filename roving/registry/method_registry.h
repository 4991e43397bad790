// Every distance method by name, for the CLI, the benchmark and the cross-checking tests.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "roving/core/distance_method.h"
#include "roving/gl_methods/gl_methods.h"

namespace roving {

// Names accepted by make_method (the CLI's --method).
std::vector<std::string> method_names();

// Throws roving::Error naming `--method`, listing the known names, for an unknown one.
// `gl` configures the GL methods (roving, viewpoint, cooperative); the others ignore it.
std::unique_ptr<DistanceMethod> make_method(const std::string& name, const GlMethodOptions& gl = {});

// True for the methods that render with GL.
bool is_gl_method(const std::string& name);

}  // namespace roving
