// shadowref/outputs/cause.hpp — the causes of the tolerance model (docs/tolerance-model.md): why a
// candidate's answer at a decided pixel may honestly differ from the reference's. The reference
// computes them (reference/causes.hpp), the judge counts them (conformance/compare/compare.hpp).
#pragma once

#include <cstdint>

namespace shadowref::outputs {

enum class Cause : std::uint8_t {
  Unexplained,     // nothing the declared technique can honestly do explains it: an error
  TexelFootprint,  // within the declared shadow map's texel footprint (× filter) of a true boundary
  DepthBias,       // within the declared bias of a contact, or on a surface steeper than the bias allows
};

constexpr const char* to_string(Cause c) {
  switch (c) {
    case Cause::Unexplained: return "unexplained";
    case Cause::TexelFootprint: return "texel footprint";
    case Cause::DepthBias: return "depth bias";
  }
  return "?";
}

}  // namespace shadowref::outputs
