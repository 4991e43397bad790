// libroving: every part folded into one shared library (roving/CMakeLists.txt); this file only
// gives the library its version, for programs that link it to check.
#include "roving/library.h"

namespace roving {

const char* library_version() { return ROVING_VERSION; }

}  // namespace roving
