// llvmpipe_renderer.hpp — the one renderer the in-process conformance tests share: OSMesa on
// llvmpipe, created on first use (a GL context and the compiled shaders) and kept for the process.
#pragma once

#include "shadowref/renderer/renderer.hpp"

namespace shadowref::test {

inline renderer::Renderer& llvmpipe_renderer() {
  static renderer::Renderer r(renderer::GlApi::OSMesa, renderer::Driver::Llvmpipe);
  return r;
}

}  // namespace shadowref::test
