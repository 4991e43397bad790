#include "roving/core/run_time_library.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include "roving/core/error.h"

namespace roving {

RunTimeLibrary::RunTimeLibrary(const std::string& soname, const std::string& what, const std::string& hint,
                               const char* fallback)
    : soname_(soname), what_(what) {
  handle_ = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_ && fallback) handle_ = dlopen(fallback, RTLD_NOW | RTLD_LOCAL);
  if (!handle_) {
    const char* why = dlerror();
    throw Error(fmt::format("{}: cannot open {} ({}); {}", what, soname, why ? why : "not found", hint));
  }
}

void* RunTimeLibrary::symbol(const char* name) const {
  void* found = dlsym(handle_, name);
  if (!found) throw Error(fmt::format("{}: {} has no {}", what_, soname_, name));
  return found;
}

}  // namespace roving
