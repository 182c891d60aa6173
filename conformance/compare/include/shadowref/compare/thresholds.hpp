// shadowref/compare/thresholds.hpp — every threshold the comparison judges by, in one place,
// each with its reason.
//
// A verdict looks at two numbers of a comparison (compare.hpp), both on decided pixels only:
//   wrong fraction  wrong / decided surface pixels (all lights together);
//   largest region  the largest 8-connected set of wrong pixels.
// Up to the pass bounds: PASS. Up to the fail bounds: a quality warning (VK-GL-CTS's
// QualityWarning; exit 1). Beyond either fail bound: FAIL.
//
// The rule that fixes every number below: a threshold that lets a known-wrong implementation pass
// is a bug. conformance/tests/teeth_table.cpp lists such implementations — the real techniques with
// fault switches on (renderer/include/shadowref/renderer/faults.hpp): z-pass with the eye in the
// volume, z-fail without caps, no bias matrix, the compare reversed, reversed-Z mistakes, acne,
// peter-panning, a half-pixel offset, the planar matrix transposed, a wrapping 8-bit stencil, … —
// and `ctest -L teeth` demands each is a FAIL on the scenes its row names, where the technique
// without faults passes; the numbers measured for the right implementations and the wrong ones
// are in conformance/README.md.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

namespace shadowref::compare {

struct Threshold {
  std::string_view name;             // the family: "exact-geometry", "shadow-map", ...
  double pass_fraction;              // wrong fraction at most this: pass
  double fail_fraction;              // above this: fail (between the two: quality warning)
  std::size_t pass_region;           // largest wrong region at most this many pixels: pass
  std::size_t fail_region;           // above this: fail
  std::string_view why;              // one sentence: why these numbers
};

// Planar projection and stencil volumes decide a pixel by rasterising exactly the triangles the
// reference intersects (the shadow matrix and the volumes come from mathlib, the camera from the
// same matrices), so on a decided pixel — every sub-pixel sample agrees and a nudge does not flip
// it — the only disagreement left is float rounding of a triangle edge passing within about 1e-6
// of a pixel centre: isolated pixels. Measured on the catalogue (llvmpipe): at most 0.0021 % and
// regions of 1 px. A camera off by half a pixel makes 0.02 % .. 0.5 %, regions of 1 .. 100 px.
inline constexpr Threshold kExactGeometry{
    "exact-geometry", 0.0001, 0.0005, 4, 16,
    "rasterised from the very triangles the reference traces: on decided pixels only float rounding at an edge "
    "through a pixel centre can differ (measured <= 0.0021 %, 1 px regions); pass <= 0.01 % and regions <= 4 px "
    "(a 5-fold margin), fail beyond 0.05 % or 16 px, which a half-pixel offset (0.02 .. 0.5 %) or a missing cap "
    "(1.8 .. 97 %) reaches"};

// A shadow map samples occluder depth at texel centres, not at the pixel's own shadow ray: a pixel
// within about one texel (projected onto the receiver, up to a few camera pixels at grazing light)
// of a shadow boundary may take its neighbour's answer, and polygon offset shifts contact shadows
// by a hair. Those errors are thin strips along boundaries. Measured on the catalogue (automatic
// map size, 3 texels per camera pixel): at most 0.088 % and regions of 14 px, both on the torus,
// whose faceted tube puts a self-shadow boundary across the whole inner ring.
inline constexpr Threshold kShadowMap{
    "shadow-map", 0.0025, 0.01, 24, 96,
    "depth is sampled at texel centres and offset by polygon offset, so pixels within about a texel of a shadow "
    "boundary may flip: thin strips (measured <= 0.088 %, regions <= 14 px); pass <= 0.25 % and regions <= 24 px, "
    "while a reversed compare or a missing bias matrix flips whole shadows (tens of percent)"};

// PCF calls a pixel lit when at least half of a 3 × 3 box of taps one texel apart pass: the
// boundary moves by up to a texel more than the single tap's (measured <= 0.088 %, regions <= 15 px).
inline constexpr Threshold kShadowMapPcf{
    "shadow-map-pcf", 0.003, 0.012, 32, 128,
    "the 3x3 percentage-closer box widens the uncertain band along boundaries by a texel on each side "
    "(measured <= 0.088 %, regions <= 15 px): a little more than a single tap, pass <= 0.3 % and regions <= 32 px"};

// The threshold of a technique (outputs::kTechniques); an unknown name
// (an engine team's own technique) gets the strictest, kExactGeometry.
const Threshold& threshold_for(std::string_view technique);

// Every threshold, for the report and for --help.
std::span<const Threshold* const> all_thresholds();

}  // namespace shadowref::compare
