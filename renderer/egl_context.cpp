// egl_context.cpp — the EGL implementation of GlContext: a 3.3 core-profile context without any
// surface (EGL_KHR_surfaceless_context), on EGL_MESA_platform_surfaceless (Mesa's software and
// GPU drivers), or on the first EGL_EXT_platform_device device where the surfaceless platform is
// missing (a GPU vendor's EGL). This is the path that outlives OSMesa (removed in Mesa 25.1).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "shadowref/renderer/gl_context.hpp"

namespace shadowref::renderer {
namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name)) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == ' ' || p[n] == '\0';
    if (starts && ends) return true;
  }
  return false;
}

template <class Fn>
Fn egl_proc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

std::string egl_error(const char* what) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string(what) + " failed (EGL error " + buf + ")";
}

class EglGlContext final : public GlContext {
 public:
  EglGlContext() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!get_display) throw GlError("EGL: eglGetPlatformDisplayEXT is missing (EGL_EXT_platform_base)");
    if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
      display_ = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    } else if (has_extension(client, "EGL_EXT_platform_device")) {
      auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
      EGLDeviceEXT device = nullptr;
      EGLint count = 0;
      if (query_devices && query_devices(1, &device, &count) && count > 0)
        display_ = get_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    }
    if (display_ == EGL_NO_DISPLAY)
      throw GlError("EGL: neither EGL_MESA_platform_surfaceless nor EGL_EXT_platform_device gives a display");
    if (!eglInitialize(display_, nullptr, nullptr)) throw GlError(egl_error("eglInitialize"));
    if (!has_extension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      eglTerminate(display_);
      throw GlError("EGL: the display lacks EGL_KHR_surfaceless_context");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      eglTerminate(display_);
      throw GlError(egl_error("eglBindAPI(EGL_OPENGL_API)"));
    }
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &configs) || configs < 1)
      config = nullptr;  // EGL_KHR_no_config_context: the context needs no config without a surface
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      eglTerminate(display_);
      throw GlError(egl_error("eglCreateContext (OpenGL 3.3 core)"));
    }
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      eglDestroyContext(display_, context_);
      eglTerminate(display_);
      throw GlError(egl_error("eglMakeCurrent (surfaceless)"));
    }
  }
  ~EglGlContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  GlProc proc_address(const char* name) const override {
    return reinterpret_cast<GlProc>(eglGetProcAddress(name));
  }
  GlApi api() const override { return GlApi::Egl; }
  void make_current() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) throw GlError(egl_error("eglMakeCurrent (surfaceless)"));
  }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> create_egl_context() { return std::make_unique<EglGlContext>(); }

}  // namespace shadowref::renderer
