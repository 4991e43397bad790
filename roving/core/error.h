// The one exception type the library throws for bad input or failed resources.
#pragma once

#include <stdexcept>
#include <string>

namespace roving {

// Thrown for every input the library refuses (unreadable or malformed file, empty model, NaN,
// bad index, absurd option). The message names the file or option, what was expected and what
// was found; executables print it as "roving: error: <message>" and exit non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace roving
