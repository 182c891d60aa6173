// shadowref/conform/mask_difference.hpp — two runs' candidate masks of one light, pixel by pixel
// (`shadowref diff`): how many pixels differ, and a picture of where.
//
// Run B is read against run A as a candidate against its reference, so the picture speaks the error
// image's colours (outputs/cause.hpp): red where B is shadowed and A lit, blue where B is lit and A
// shadowed, magenta where one has a surface and the other none, yellow for a byte that differs
// within one mask class (a value outside the contract in either). Pixels where the two agree show
// the mask dimmed, as the error image's background does (outputs::kDimmedLit and its neighbours).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/image.hpp"

namespace shadowref::conform {

struct MaskDifferenceClass {
  std::string_view name;
  outputs::Rgb colour;
  std::string_view legend;
};

// Every colour of the difference picture, for its legend (the HTML page of `diff`).
inline constexpr std::array<MaskDifferenceClass, 4> kMaskDifferenceClasses{{
    {"shadowed in B", outputs::error_colour(outputs::ErrorClass::FalseShadow), "B shadowed, A lit"},
    {"lit in B", outputs::error_colour(outputs::ErrorClass::FalseLight), "B lit, A shadowed"},
    {"coverage", outputs::error_colour(outputs::ErrorClass::Coverage), "a surface in one, none in the other"},
    {"other value", outputs::error_colour(outputs::ErrorClass::Acne), "another byte in the same mask class"},
}};

// The pixels whose bytes differ between `a` and `b` (grey masks of one size; a std::invalid_argument
// otherwise, which callers rule out by checking the sizes first).
std::size_t count_differing_pixels(const outputs::Image8& a, const outputs::Image8& b);

// The RGB picture of where `a` and `b` differ (the same preconditions).
outputs::Image8 paint_mask_difference(const outputs::Image8& a, const outputs::Image8& b);

}  // namespace shadowref::conform
