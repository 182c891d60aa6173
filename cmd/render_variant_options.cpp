// render_variant_options.cpp — our renderer's correct variants on the command line, one definition
// for `shadowref render` and `shadowref conform`: a randomized kernel, the depth pass's faces, a
// shadow-atlas guard band, a normal offset, distance cubes and light views of our own (turned, their
// grid moved, warped by LiSPSM), and the light matrices declared, each declared in candidate.json by
// the renderer.
#include <CLI/CLI.hpp>

#include <string>

#include "command.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref::cli {

void add_render_variant_options(CLI::App& cmd, RenderVariantArgs& args) {
  cmd.add_option("--random-taps", args.random_taps,
                 "0: every filter on its fixed grid; N (a square, 4..64): our PCF and PCSS take N taps of a Vogel disk "
                 "turned per pixel by noise (declared \"sampling\": \"random\")")
      ->check(random_taps_check())
      ->capture_default_str();
  cmd.add_option("--depth-faces", args.depth_faces,
                 "the faces our hard shadow maps' depth pass draws on closed casters: back (front faces culled), "
                 "front (back faces culled) or both; declared as \"depth_faces\"")
      ->check(CLI::IsMember({"back", "front", "both"}))
      ->capture_default_str();
  cmd.add_option("--guard-band", args.guard_band,
                 "texels each light's map gains along every side beyond its view, as a shadow-atlas tile's guard band "
                 "(the view keeps its texel grid); declared per light as \"atlas_tile\"")
      ->check(CLI::Range(0, outputs::kMaxGuardBandTexels))
      ->capture_default_str();
  cmd.add_option("--normal-offset-texels", args.normal_offset_texels,
                 "our hard maps' normal offset: each lookup moved along the surface normal (toward the light) by this "
                 "many texels of the map there; declared as \"normal_offset_texels\"")
      ->check(CLI::Range(0.0, 8.0))
      ->capture_default_str();
  cmd.add_option("--cube-depth", args.cube_depth,
                 "what point lights' cubes hold under the depth-texture maps: window (the light projection's depth) "
                 "or distance (from the light over a range, written with gl_FragDepth, as engines' distance cubes); "
                 "declared per light as \"depth\", \"depth_range\" and \"depth_bias\"")
      ->check(CLI::IsMember({"window", "distance"}))
      ->capture_default_str();
  cmd.add_option("--view-turn", args.view_turn,
                 "degrees each light view of our maps turns about its axis, as an engine's own views may (the view "
                 "widened to cover the pack's: texels up to 1.41 times wider); declared \"light_views\": \"own\"")
      ->check(CLI::Range(-90.0, 90.0))
      ->capture_default_str();
  cmd.add_option("--view-phase", args.view_phase,
                 "texels our maps' texel grid moves along both axes of each light view, as an engine's own views may "
                 "place it; declared \"light_views\": \"own\"")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd.add_flag("--declare-light-matrices", args.declare_light_matrices,
               "declare our shadow maps' light matrices as an engine that knows its own may: \"light_views\": "
               "\"declared\" with each light's view and projection as drawn and its map size, so that the judge "
               "knows the exact texel grid");
  cmd.add_flag("--lispsm", args.lispsm,
               "warp directional lights' maps by light space perspective shadow maps (Wimmer et al. 2004) in the "
               "techniques that are not cascaded: texels small near the camera and large far from it; declared "
               "\"light_views\": \"own\" for those lights, or their matrices with --declare-light-matrices");
}

void apply_render_variants(const RenderVariantArgs& a, int shadow_map_size, renderer::RenderOptions& options) {
  if (shadow_map_size + 2 * a.guard_band > outputs::kMaxShadowMapSize)
    throw BadInput("--guard-band " + std::to_string(a.guard_band) + ": a map of " + std::to_string(shadow_map_size) +
                   " texels with the band on both sides exceeds " + std::to_string(outputs::kMaxShadowMapSize) + " texels");
  options.random_taps = a.random_taps;
  options.depth_faces = outputs::depth_faces_from(a.depth_faces).value();  // CLI::IsMember checked it
  options.guard_band_texels = a.guard_band;
  options.normal_offset_texels = a.normal_offset_texels;
  options.cube_depth = a.cube_depth == "distance" ? outputs::StoredDepth::Distance : outputs::StoredDepth::Window;
  options.view_turn_degrees = a.view_turn;
  options.view_phase_texels = a.view_phase;
  options.declare_light_matrices = a.declare_light_matrices;
  options.lispsm = a.lispsm;
}

}  // namespace shadowref::cli
