// OSMesa and EGL offscreen contexts (GL 4.5 core profile; rendering goes to FBOs).
#include "gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "roving/core/error.h"
#include "roving/core/run_time_library.h"

namespace roving::gl {
namespace {

// OSMesa is opened when a context is first asked for, not linked: it pulls in LLVM (llvmpipe),
// whose relocations alone cost ~50 MB of resident memory and 20 ms at start, which every run of
// a CPU method would pay for nothing.
struct OsMesaLibrary {
  decltype(&OSMesaCreateContextAttribs) create_context = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaDestroyContext) destroy_context = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;
  decltype(&OSMesaGetCurrentContext) get_current_context = nullptr;
};

const OsMesaLibrary& osmesa() {
  static const OsMesaLibrary library = [] {
    const RunTimeLibrary osmesa("libOSMesa.so.8", "osmesa", "install libosmesa6 or use --backend egl", "libOSMesa.so");
    OsMesaLibrary l;
    osmesa.load(l.create_context, "OSMesaCreateContextAttribs");
    osmesa.load(l.make_current, "OSMesaMakeCurrent");
    osmesa.load(l.destroy_context, "OSMesaDestroyContext");
    osmesa.load(l.get_proc_address, "OSMesaGetProcAddress");
    osmesa.load(l.get_current_context, "OSMesaGetCurrentContext");
    return l;
  }();
  return library;
}

class OsMesaContext final : public Context {
 public:
  OsMesaContext() : osmesa_(osmesa()) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    context_ = osmesa_.create_context(attributes, nullptr);
    if (!context_)
      throw Error("osmesa: cannot create a GL 4.5 core context (OSMesaCreateContextAttribs failed)");
    // OSMesa needs a colour buffer to be current; all rendering goes to FBOs, so 1 x 1 will do.
    if (!osmesa_.make_current(context_, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
      osmesa_.destroy_context(context_);
      throw Error("osmesa: cannot make the context current");
    }
  }
  ~OsMesaContext() override { osmesa_.destroy_context(context_); }

  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(osmesa_.get_proc_address(name));
  }
  std::string platform() const override { return "osmesa"; }
  void make_current() override {
    if (osmesa_.get_current_context() != context_ &&
        !osmesa_.make_current(context_, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
      throw Error("osmesa: cannot make the context current again");
    }
  }

 private:
  const OsMesaLibrary& osmesa_;
  OSMesaContext context_ = nullptr;
  unsigned char pixel_[4] = {};
};

class EglContext final : public Context {
 public:
  EglContext() {
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const auto has = [&](const char* name) {
      return client_extensions && std::strstr(client_extensions, name);
    };
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display)
      throw Error("egl: eglGetPlatformDisplayEXT is missing (no EGL_EXT_platform_base)");

    // A device display reaches a real GPU; Mesa's software device is skipped in its favour only
    // when a hardware one exists, and surfaceless is the fallback.
    std::string failures;
    if (has("EGL_EXT_platform_device")) {
      auto query_devices =
          reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      EGLint count = 0;
      if (query_devices && query_devices(0, nullptr, &count) && count > 0) {
        std::vector<EGLDeviceEXT> devices(count);
        query_devices(count, devices.data(), &count);
        for (EGLDeviceEXT device : devices) {
          if (try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr), "egl-device",
                          failures))
            return;
        }
      }
    }
    if (has("EGL_MESA_platform_surfaceless") &&
        try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                    "egl-surfaceless", failures)) {
      return;
    }
    throw Error("egl: no display gives a GL 4.5 core context (" +
                (failures.empty() ? "no device or surfaceless platform" : failures) + ")");
  }
  ~EglContext() override {
    if (eglGetCurrentContext() == context_)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // Not eglTerminate: a display is one per device and process, shared by every context on it
    // (a picture's beside a method's), and terminating it would invalidate theirs.
  }

  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
  }
  std::string platform() const override { return platform_; }
  void make_current() override {
    if (eglGetCurrentContext() != context_ &&
        !eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw Error(
          fmt::format("{}: cannot make the context current again (0x{:x})", platform_, eglGetError()));
    }
  }

 private:
  bool try_display(EGLDisplay display, const char* platform, std::string& failures) {
    const auto fail = [&](const char* step) {
      failures += fmt::format("{}{}: {} failed (0x{:x})", failures.empty() ? "" : "; ", platform, step,
                              eglGetError());
      return false;
    };
    if (display == EGL_NO_DISPLAY) return fail("eglGetPlatformDisplay");
    if (!eglInitialize(display, nullptr, nullptr)) return fail("eglInitialize");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(OpenGL)");
    const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    eglChooseConfig(display, config_attributes, &config, 1, &configs);
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    // Without EGL_KHR_no_config_context a config is needed; surfaceless Mesa accepts none.
    EGLContext context = eglCreateContext(display, configs > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                          context_attributes);
    if (context == EGL_NO_CONTEXT) {
      eglTerminate(display);
      return fail("eglCreateContext(4.5 core)");
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      eglDestroyContext(display, context);
      eglTerminate(display);
      return fail("eglMakeCurrent(surfaceless)");
    }
    display_ = display;
    context_ = context;
    platform_ = platform;
    return true;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string platform_;
};

// llvmpipe rasterises on LP_NUM_THREADS threads of its own (default: one a core) and reads the
// variable once, when its first context is made. The GL methods already keep two cores busy: this
// thread drives GL while the CPU work runs beside it (run_beside). On two cores more rasteriser
// threads only take turns with that work and add a hand-off to every draw, so there llvmpipe
// rasterises in this thread (cooperative 24x12, bunny vs 10,459: 0.31 -> 0.28 s). A user's own
// setting wins; more cores keep Mesa's default, and so does a process whose GL works alone
// (roving's compute path, 400,000 samples of the bunny against 10,459 faces: 3.05 s with no
// threads of llvmpipe's own, 1.78 s with two).
void rasterise_here_on_two_cores() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::thread::hardware_concurrency() <= 2) ::setenv("LP_NUM_THREADS", "0", /*overwrite=*/0);
  });
}

}  // namespace

std::unique_ptr<Context> make_context(GlBackend backend, bool gl_works_alone) {
  if (!gl_works_alone) rasterise_here_on_two_cores();
  if (backend == GlBackend::OSMesa) return std::make_unique<OsMesaContext>();
  return std::make_unique<EglContext>();
}

}  // namespace roving::gl
