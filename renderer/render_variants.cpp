// render_variants.cpp — the table of our renders' correct variants (render_variants.hpp): each
// RenderOptions field a user chooses, with its flag, accepted values, help and report key.
#include "shadowref/renderer/render_variants.hpp"

#include <array>

#include "shadowref/outputs/limits.hpp"

namespace shadowref::renderer {
namespace {

// A number in [min, max].
RenderVariant number(std::string_view flag, std::string_view key, std::string_view help, RenderVariant::Field field,
                     double min, double max) {
  return RenderVariant{flag, key, help, field, min, max, nullptr, {}};
}
// A whole number that `problem` accepts (returns "" for), `accepts` its summary.
RenderVariant checked(std::string_view flag, std::string_view key, std::string_view help, RenderVariant::Field field,
                      std::string (*problem)(long long), std::string_view accepts) {
  return RenderVariant{flag, key, help, field, 0.0, 0.0, problem, accepts};
}
// A switch (a flag without a value) or one of an enumeration's names.
RenderVariant choice(std::string_view flag, std::string_view key, std::string_view help, RenderVariant::Field field) {
  return RenderVariant{flag, key, help, field, 0.0, 0.0, nullptr, {}};
}

const std::array<RenderVariant, 9> kVariants{
    checked("--random-taps", "random_taps",
            "0: every filter on its fixed grid; N (a square, 4..64): our PCF and PCSS take N taps of a Vogel disk turned "
            "per pixel by noise (declared \"sampling\": \"random\")",
            &RenderOptions::random_taps, outputs::random_taps_problem, "0 or a square 4..64"),
    choice("--depth-faces", "depth_faces",
           "the faces our hard shadow maps' depth pass draws on closed casters: back (front faces culled), front (back "
           "faces culled) or both; declared as \"depth_faces\"",
           &RenderOptions::depth_faces),
    number("--guard-band", "guard_band_texels",
           "texels each light's map gains along every side beyond its view, as a shadow-atlas tile's guard band (the "
           "view keeps its texel grid); declared per light as \"atlas_tile\"",
           &RenderOptions::guard_band_texels, 0, outputs::kMaxGuardBandTexels),
    number("--normal-offset-texels", "normal_offset_texels",
           "our hard maps' normal offset: each lookup moved along the surface normal (toward the light) by this many "
           "texels of the map there; declared as \"normal_offset_texels\"",
           &RenderOptions::normal_offset_texels, 0.0, 8.0),
    choice("--cube-depth", "cube_depth",
           "what point lights' cubes hold under the depth-texture maps: window (the light projection's depth) or "
           "distance (from the light over a range, written with gl_FragDepth, as engines' distance cubes); declared per "
           "light as \"depth\", \"depth_range\" and \"depth_bias\"",
           &RenderOptions::cube_depth),
    number("--view-turn", "view_turn_degrees",
           "degrees each light view of our maps turns about its axis, as an engine's own views may (the view widened to "
           "cover the pack's: texels up to 1.41 times wider); declared \"light_views\": \"own\"",
           &RenderOptions::view_turn_degrees, -90.0, 90.0),
    number("--view-phase", "view_phase_texels",
           "texels our maps' texel grid moves along both axes of each light view, as an engine's own views may place "
           "it; declared \"light_views\": \"own\"",
           &RenderOptions::view_phase_texels, 0.0, 1.0),
    choice("--declare-light-matrices", "declare_light_matrices",
           "declare our shadow maps' light matrices as an engine that knows its own may: \"light_views\": \"declared\" "
           "with each light's view and projection as drawn and its map size, so that the judge knows the exact texel "
           "grid",
           &RenderOptions::declare_light_matrices),
    choice("--lispsm", "lispsm",
           "warp directional lights' maps by light space perspective shadow maps (Wimmer et al. 2004) in the techniques "
           "that are not cascaded: texels small near the camera and large far from it; declared \"light_views\": \"own\" "
           "for those lights, or their matrices with --declare-light-matrices",
           &RenderOptions::lispsm),
};

constexpr std::array kDepthFaces{outputs::DepthFaces::Back, outputs::DepthFaces::Front, outputs::DepthFaces::Both};
constexpr std::array kStoredDepths{outputs::StoredDepth::Window, outputs::StoredDepth::Distance};

}  // namespace

std::span<const RenderVariant> render_variants() { return kVariants; }

void copy_render_variants(const RenderOptions& from, RenderOptions& to) {
  for (const RenderVariant& v : kVariants) std::visit([&](auto member) { to.*member = from.*member; }, v.field);
}

std::span<const outputs::DepthFaces> all_values(outputs::DepthFaces) { return kDepthFaces; }
std::span<const outputs::StoredDepth> all_values(outputs::StoredDepth) { return kStoredDepths; }

}  // namespace shadowref::renderer
