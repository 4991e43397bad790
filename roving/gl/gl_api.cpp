// Loading of the GL entry-point table.
#include "gl_api.h"

#include <fmt/format.h>

#include "roving/core/error.h"

namespace roving::gl {

void Api::load(const std::function<void*(const char*)>& get, const std::string& backend) {
#define ROVING_GL_LOAD(type, name)                \
  name = reinterpret_cast<type>(get("gl" #name)); \
  if (!name) throw Error(fmt::format("{}: GL entry point gl{} not found", backend, #name));
  ROVING_GL_FUNCTIONS(ROVING_GL_LOAD)
#undef ROVING_GL_LOAD
}

}  // namespace roving::gl
