// shadowref/outputs/cause.hpp — the causes of the tolerance model (docs/tolerance-model.md): why a
// candidate's answer at a decided pixel may honestly differ from the reference's. The reference
// computes them (reference/causes.hpp), the judge counts them (conformance/compare/compare.hpp).
#pragma once

#include <cstdint>

namespace shadowref::outputs {

enum class Cause : std::uint8_t {
  Unexplained,     // nothing the declared technique can honestly do explains it: an error
  TexelFootprint,  // within the declared shadow map's texel footprint (× filter) of a true boundary
  DepthBias,       // within the bias a correct map needs (and the candidate declares) of a contact
  Acne,            // unexplained: a false shadow that the receiver's own surface, stored with less
                   // bias than a correct map needs, casts on itself (self-shadowing); an error
};

// Whether `c` tolerates the pixel (the explained causes); Unexplained and Acne are errors.
constexpr bool explains(Cause c) { return c == Cause::TexelFootprint || c == Cause::DepthBias; }

constexpr const char* to_string(Cause c) {
  switch (c) {
    case Cause::Unexplained: return "unexplained";
    case Cause::TexelFootprint: return "texel footprint";
    case Cause::DepthBias: return "depth bias";
    case Cause::Acne: return "self-shadowing (acne)";
  }
  return "?";
}

}  // namespace shadowref::outputs
