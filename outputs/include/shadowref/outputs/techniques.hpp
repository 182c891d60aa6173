// shadowref/outputs/techniques.hpp — the technique names of the contract, the one list.
//
// A technique name is what a scene's `expect` keys, a candidate's declaration, the renderer's
// `--technique`, the judge's threshold and the CTest case names all use. The renderer's table
// (renderer/renderer.cpp) is checked at compile time against this list, entry by entry; the CMake
// test registration reads the quoted names below (cmake/ContractNames.cmake), so keep one entry per
// line in the form {"name", TechniqueFamily::...}.
#pragma once

#include <array>
#include <string_view>

namespace shadowref::outputs {

// How a technique decides a pixel, which fixes how it is judged (conformance/compare/thresholds.hpp).
enum class TechniqueFamily {
  ExactGeometry,  // rasterises the very triangles the reference traces: planar, stencil volumes
  ShadowMap,      // one depth compare per pixel against a map of texels
  ShadowMapPcf,   // a filtered compare (percentage-closer filtering)
  SoftShadow,     // a filter that follows the light's size (PCSS, VSM): judged as visibility too
};

struct TechniqueName {
  std::string_view name;
  TechniqueFamily family;
  // Cascaded shadow maps: a directional light's map split along the camera's depth
  // (mathlib/cascades.hpp), each pixel judged by the texels of its cascade; other lights as the
  // plain shadow map.
  bool cascaded = false;
};

// clang-format off
inline constexpr std::array<TechniqueName, 13> kTechniques{{
    {"planar", TechniqueFamily::ExactGeometry},
    {"volume-zpass", TechniqueFamily::ExactGeometry},
    {"volume-zfail", TechniqueFamily::ExactGeometry},
    {"volume-zfail-clamp", TechniqueFamily::ExactGeometry},
    {"volume-robust", TechniqueFamily::ExactGeometry},
    {"volume-finite", TechniqueFamily::ExactGeometry},
    {"shadowmap", TechniqueFamily::ShadowMap},
    {"shadowmap-pcf", TechniqueFamily::ShadowMapPcf},
    {"shadowmap-rgba8", TechniqueFamily::ShadowMap},
    {"csm", TechniqueFamily::ShadowMap, true},
    {"csm-pcf", TechniqueFamily::ShadowMapPcf, true},
    {"pcss", TechniqueFamily::SoftShadow},
    {"vsm", TechniqueFamily::SoftShadow},
}};
// clang-format on

// The entry called `name`, or nullptr.
constexpr const TechniqueName* find_technique_name(std::string_view name) {
  for (const TechniqueName& t : kTechniques)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace shadowref::outputs
