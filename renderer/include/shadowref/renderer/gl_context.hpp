// shadowref/renderer/gl_context.hpp — the one small interface behind which an OpenGL 3.3 core
// context is created, so that the renderer does not depend on how it got one.
//
// Two implementations:
//   * OSMesa (osmesa_context.cpp): Mesa's off-screen library, gone from Mesa 25.1;
//   * EGL surfaceless (egl_context.cpp): EGL_MESA_platform_surfaceless, and, where that platform
//     is missing (a GPU vendor's EGL), EGL_EXT_platform_device on the first device.
// Neither context's default framebuffer is used for rendering: the renderer draws into its own
// framebuffer object (RGBA8 colour, DEPTH24_STENCIL8), because an EGL surfaceless context has no
// default framebuffer at all, and one code path keeps both backends pixel-identical.
//
// Mesa's Gallium driver is chosen with GALLIUM_DRIVER, read when the first context creates its
// screen; create_gl_context() sets it and refuses a different driver later in the same process
// (the first choice would silently stay in force).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace shadowref::renderer {

// Any failure of the GL side: no context, a shader that does not compile, an incomplete FBO.
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A GL entry point as returned by OSMesaGetProcAddress / eglGetProcAddress; cast to its real type.
using GlProc = void (*)();

enum class GlApi { OSMesa, Egl };
// Mesa's Gallium driver. Native leaves GALLIUM_DRIVER alone (a GPU driver through EGL).
enum class Driver { Llvmpipe, Softpipe, Native };

const char* to_string(GlApi api);
const char* to_string(Driver driver);
// Parse "osmesa" | "egl" and "llvmpipe" | "softpipe" | "native"; throw std::invalid_argument.
GlApi parse_gl_api(std::string_view name);
Driver parse_driver(std::string_view name);

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // The address of a GL function ("glDrawArrays"), or nullptr.
  virtual GlProc proc_address(const char* name) const = 0;
  // Makes this context current on the calling thread (several renderers may share a process: each
  // makes its own current before it draws). Throws GlError.
  virtual void make_current() = 0;
  virtual GlApi api() const = 0;
};

// A current OpenGL 3.3 core-profile context on `api`, with `driver` selected first.
// Throws GlError when the context cannot be created, or when the renderer string does not name
// the requested Mesa driver (so that a run never claims llvmpipe while using something else).
std::unique_ptr<GlContext> create_gl_context(GlApi api, Driver driver);

// Implementations (one source file each); create_gl_context() is the way in.
std::unique_ptr<GlContext> create_osmesa_context();
std::unique_ptr<GlContext> create_egl_context();

}  // namespace shadowref::renderer
