// A shared library opened when first needed instead of linked: for one whose loading would cost
// every run at start what few runs use (OSMesa pulls in LLVM; libmatio, through HDF5, curl and
// GnuTLS). It stays open for the process's life.
#pragma once

#include <string>

namespace roving {

class RunTimeLibrary {
 public:
  // Opens `soname`, else `fallback` where one is given. Throws roving::Error "`what`: cannot open
  // `soname` (why); `hint`".
  RunTimeLibrary(const std::string& soname, const std::string& what, const std::string& hint,
                 const char* fallback = nullptr);

  // Sets `function` to the library's symbol `name`; throws "`what`: `soname` has no `name`".
  template <class Function>
  void load(Function& function, const char* name) const {
    function = reinterpret_cast<Function>(symbol(name));
  }

 private:
  void* symbol(const char* name) const;

  void* handle_ = nullptr;
  std::string soname_, what_;
};

}  // namespace roving
