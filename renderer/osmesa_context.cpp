// osmesa_context.cpp — the OSMesa implementation of GlContext: a 3.3 core-profile context with
// an RGBA8 colour buffer and 24-bit depth + 8-bit stencil (the default framebuffer the brief asks
// for; the renderer itself draws into an FBO of the same formats, see gl_context.hpp).
// OSMesa includes <GL/gl.h>, which must not meet <GL/glcorearb.h>: this file sees only osmesa.h.
#include <GL/osmesa.h>

#include <array>
#include <memory>
#include <vector>

#include "shadowref/renderer/gl_context.hpp"

namespace shadowref::renderer {
namespace {

class OSMesaGlContext final : public GlContext {
 public:
  OSMesaGlContext() {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                           OSMESA_DEPTH_BITS, 24,
                           OSMESA_STENCIL_BITS, 8,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 3,
                           OSMESA_CONTEXT_MINOR_VERSION, 3,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw GlError("OSMesaCreateContextAttribs failed: no OpenGL 3.3 core profile from OSMesa");
    // A small default framebuffer: only needed to make the context current (rendering goes to FBOs).
    buffer_.assign(static_cast<std::size_t>(kSize) * kSize * 4, 0);
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize)) {
      OSMesaDestroyContext(ctx_);
      throw GlError("OSMesaMakeCurrent failed");
    }
  }
  ~OSMesaGlContext() override {
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(ctx_);
  }
  GlProc proc_address(const char* name) const override {
    return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
  }
  GlApi api() const override { return GlApi::OSMesa; }
  void make_current() override {
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize)) throw GlError("OSMesaMakeCurrent failed");
  }

 private:
  static constexpr int kSize = 16;
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context() { return std::make_unique<OSMesaGlContext>(); }

}  // namespace shadowref::renderer
