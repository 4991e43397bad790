// Offscreen GL 4.5 core contexts: OSMesa, or EGL (device platform, then surfaceless).
#pragma once

#include <memory>
#include <string>

#include "roving/gl/depth_renderer.h"

namespace roving::gl {

class Context {
 public:
  virtual ~Context() = default;
  // Address of a GL entry point in this context's GL.
  virtual void* proc_address(const char* name) const = 0;
  virtual std::string platform() const = 0;  // e.g. "osmesa", "egl-device", "egl-surfaceless"
  // Makes this context current again if another one (a picture's, say) was made current since.
  virtual void make_current() = 0;
};

// Creates the context and makes it current on the calling thread; throws roving::Error with the
// step that failed. `gl_works_alone`: the CPU threads wait while the GL works (the compute path),
// so llvmpipe keeps its own threads on any machine (see gl_context.cpp); only the process's
// first context decides.
std::unique_ptr<Context> make_context(GlBackend backend, bool gl_works_alone = false);

}  // namespace roving::gl
