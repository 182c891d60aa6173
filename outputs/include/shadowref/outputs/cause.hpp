// shadowref/outputs/cause.hpp — the causes of the tolerance model (docs/tolerance-model.md): why a
// candidate's answer at a decided pixel may honestly differ from the reference's, and the one table
// of what the judge shows for each wrong pixel. The reference computes the causes
// (reference/causes.hpp), the judge counts them (conformance/compare/compare.hpp) and paints them;
// the report (JSON and HTML), the pack's README and `shadowref compare --help` read the table below.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace shadowref::outputs {

enum class Cause : std::uint8_t {
  Unexplained,     // nothing the declared technique can honestly do explains it: an error
  TexelFootprint,  // within the declared shadow map's texel footprint (× filter) of a true boundary
  DepthBias,       // within the bias a correct map needs (and the candidate declares) of a contact
  Acne,            // unexplained: a false shadow that the receiver's own surface, stored with less
                   // bias than a correct map needs, casts on itself (self-shadowing); an error
};

// What the error image shows at a pixel the judge looked at and found wrong (or did not judge): an
// unexplained error by its kind, an error by its cause. The values index kErrorClasses.
enum class ErrorClass : std::uint8_t {
  FalseShadow,  // unexplained, reference lit, candidate shadowed
  Acne,         // unexplained false shadow of the receiver on itself (Cause::Acne)
  FalseLight,   // unexplained, reference shadowed, candidate lit
  Coverage,     // a surface in one, none in the other (no shadow cause explains it)
  Texel,        // explained: Cause::TexelFootprint
  Bias,         // explained: Cause::DepthBias
  Undecided,    // not judged: the reference's undecided pixels
};

using Rgb = std::array<std::uint8_t, 3>;

struct ErrorClassRow {
  ErrorClass id;
  std::string_view name;         // a short name, and the key of the README template's placeholders
  Rgb colour;                    // in the error image (error.png)
  std::string_view colour_name;  // the colour in words, for text that cannot show it
  std::string_view legend;       // what the colour means, for every legend (HTML, README, --help)
  std::string_view json_key;     // report.json's count of such pixels (a mask's metrics); empty: none
  bool explained;                // tolerated: counted as explained, never as an error
};

// The table, in ErrorClass order (the order every legend lists them in).
// clang-format off
inline constexpr std::array<ErrorClassRow, 7> kErrorClasses{{
    {ErrorClass::FalseShadow, "false shadow", {235, 50, 50}, "red",
     "false shadow, unexplained (reference lit)", "false_shadow", false},
    {ErrorClass::Acne, "acne", {255, 235, 40}, "yellow",
     "false shadow, unexplained: self-shadowing (acne)", "unexplained_acne", false},
    {ErrorClass::FalseLight, "false light", {40, 120, 255}, "blue",
     "false light, unexplained (reference shadowed)", "false_light", false},
    {ErrorClass::Coverage, "coverage", {230, 40, 230}, "magenta",
     "coverage: a surface in one, none in the other", "coverage", false},
    {ErrorClass::Texel, "texel footprint", {240, 170, 20}, "orange",
     "explained: within the texel footprint of a real boundary", "explained_texel", true},
    {ErrorClass::Bias, "depth bias", {30, 200, 200}, "cyan",
     "explained: within the bias a correct map needs at a contact", "explained_bias", true},
    {ErrorClass::Undecided, "undecided", {70, 105, 70}, "dark green",
     "undecided: not judged", "", false},
}};
// clang-format on

constexpr const ErrorClassRow& error_class(ErrorClass c) { return kErrorClasses[static_cast<std::size_t>(c)]; }
constexpr const Rgb& error_colour(ErrorClass c) { return error_class(c).colour; }

// The row of a wrong pixel's cause; nullptr for Cause::Unexplained (painted by its kind instead).
constexpr const ErrorClassRow* error_class_of(Cause c) {
  switch (c) {
    case Cause::Unexplained: return nullptr;
    case Cause::TexelFootprint: return &error_class(ErrorClass::Texel);
    case Cause::DepthBias: return &error_class(ErrorClass::Bias);
    case Cause::Acne: return &error_class(ErrorClass::Acne);
  }
  return nullptr;
}

// Whether `c` tolerates the pixel (the explained causes); Unexplained and Acne are errors.
constexpr bool explains(Cause c) { return error_class_of(c) != nullptr && error_class_of(c)->explained; }

// The error image's background: the reference dimmed, by its mask value (shadowed, no surface, lit),
// under the colours above.
inline constexpr Rgb kDimmedShadowed{55, 55, 55}, kDimmedNoSurface{28, 28, 42}, kDimmedLit{150, 150, 150};

// The row called `name` (ErrorClassRow::name), or nullptr.
constexpr const ErrorClassRow* find_error_class(std::string_view name) {
  for (const ErrorClassRow& r : kErrorClasses)
    if (r.name == name) return &r;
  return nullptr;
}

// "rgb(R, G, B)", the colour as CSS and the legends write it.
std::string rgb_text(const Rgb& c);

// The table as one line of text for a command's help: "red = false shadow, unexplained (reference
// lit), yellow = ..., dark green = undecided: not judged; grey: the dimmed reference".
std::string error_colours_line();

// The cause's name: "unexplained", or its row's name.
constexpr std::string_view to_string(Cause c) {
  const ErrorClassRow* r = error_class_of(c);
  return r ? r->name : std::string_view("unexplained");
}

}  // namespace shadowref::outputs
