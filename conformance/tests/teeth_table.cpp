// teeth_table.cpp — the rows (teeth_table.hpp). Scenes are those the row must FAIL on, chosen from
// `conformance_teeth --survey` (every row on the whole default catalogue; conformance/README.md
// lists what it found). Each row's `why` says what the bug does there.
#include "teeth_table.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

namespace shadowref::teeth {
namespace {

using renderer::CompareFault;
using renderer::Faults;
using renderer::CubeFault;
using renderer::FitFault;

// The production switches with those `set` turns on (nested designated initializers would have
// GCC 12 warn about every family left out).
template <class Set>
constexpr Faults on(Set set) {
  Faults f;
  set(f);
  return f;
}

// clang-format off
constexpr Row kRows[] = {
    // ---- planar projected shadows -------------------------------------------------------------
    {.name = "planar-d3dx-transposed", .technique = "planar",
     .faults = on([](Faults& f) { f.planar.matrix_transposed = true; }), .convention = "gl",
     .scenes = "camera_at_light ground_sphere",
     .field_class = "the D3DX matrix transposed (row-vector layout in a column-vector pipeline)",
     .why = "the transposed matrix is no projection onto the ground: shadows appear where none may be seen (the "
            "camera at the light) or land elsewhere (the sphere's)"},
    {.name = "planar-double-darkening", .technique = "planar",
     .faults = on([](Faults& f) { f.planar.darken_every_fragment = true; }), .convention = "gl",
     .scenes = "cube_seams ground_sphere",
     .field_class = "planar shadows darkened twice where the caster's projection overlaps itself (no stencil)",
     .why = "every closed caster projects its near and far sides onto the same receiver pixels, so its whole "
            "shadow is darkened twice; the mask reads a shadow where a pixel was darkened exactly once, and "
            "loses all of it"},
    {.name = "planar-directional-as-point", .technique = "planar",
     .faults = on([](Faults& f) { f.planar.directional_as_point = true; }), .convention = "gl",
     .scenes = "directional_light offscreen_caster",
     .field_class = "a light with w = 0 treated as a point",
     .why = "the sun's direction vector is taken for the position of a point light about a unit from the origin, "
            "low beside or among the casters: their shadows spread from it instead of falling parallel"},

    // ---- stencil shadow volumes ---------------------------------------------------------------
    {.name = "zpass-eye-inside-volume", .technique = "volume-robust",
     .faults = on([](Faults& f) { f.volume.robust_always_zpass = true; }), .convention = "gl",
     .scenes = "camera_in_shadow",
     .field_class = "z-pass with the eye inside a shadow volume",
     .why = "the camera stands under the plate, inside its shadow volume: depth-pass counts start from 0 instead "
            "of 1, and lit and shadowed swap over the whole view"},
    {.name = "zfail-without-caps", .technique = "volume-zfail",
     .faults = on([](Faults& f) { f.volume.no_caps = true; }), .convention = "gl",
     .scenes = "directional_light ground_sphere",
     .field_class = "z-fail without caps",
     .why = "depth-fail counts the volume faces behind a surface: where the missing dark cap (or light cap) was "
            "one of them, the count is off by one, in or out of the shadow"},
    {.name = "stencil-8bit-wraps", .technique = "volume-zfail",
     .faults = {}, .convention = "gl",
     .scenes = "nested_256_volumes",
     .field_class = "an 8-bit stencil that wraps",
     .why = "256 nested volumes count 256 = 0 (mod 256): the innermost shadow reads as lit. Judged as a technique "
            "claiming exact counts; its control, judged as itself, is the catalogue's XFAIL that says so",
     .judged_as = "volume-exact-count"},
    {.name = "irrlicht-light-position-as-direction", .technique = "volume-zfail",
     .faults = on([](Faults& f) { f.volume.light_position_as_direction = true; }), .convention = "gl",
     .scenes = "cube_seams light_near_caster",
     .field_class = "silhouettes classified with the light position used as a direction (Irrlicht 1.8)",
     .why = "facing is tested against (x, y, z, 0), the direction from the origin to the light, not toward the "
            "light from each face: near a caster that is not at the origin the silhouette is wrong, the volume "
            "is not closed, and shadows fall on the wrong faces"},
    {.name = "saturating-stencil", .technique = "volume-zfail",
     .faults = on([](Faults& f) { f.volume.saturating_stencil = true; }), .convention = "gl",
     .scenes = "cube_seams ground_sphere",
     .field_class = "saturating stencil ops (GL_INCR / GL_DECR) with two-sided stencil",
     .why = "one pass of two-sided stencil meets a volume's faces in drawing order: where a decrement comes "
            "first it saturates at 0 and the increment leaves +1, a false shadow behind the volume"},
    {.name = "volume-casters-culled-to-view", .technique = "volume-zfail",
     .faults = on([](Faults& f) { f.volume.cull_casters_outside_view = true; }), .convention = "gl",
     .scenes = "offscreen_caster skinned_offscreen",
     .field_class = "casters outside the view frustum culled from the shadow pass",
     .why = "the pole, and the posed character, stand out of the camera's view and cast long shadows across the visible "
            "ground"},
    {.name = "half-pixel-offset", .technique = "volume-zfail",
     .faults = on([](Faults& f) { f.camera.half_pixel_offset = true; }), .convention = "gl",
     .scenes = "offscreen_caster shadow_on_object",
     .field_class = "a half-pixel offset (Direct3D 9 pixel centres)",
     .why = "every edge moves by half a pixel: along long object and shadow edges whole runs of decided pixels "
            "change side"},

    // ---- shadow maps --------------------------------------------------------------------------
    {.name = "shadowmap-compare-reversed", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.compare = CompareFault::Reversed; }), .convention = "gl",
     .scenes = "ground_sphere",
     .field_class = "the shadow-map compare reversed (GL_GEQUAL for GL_LEQUAL)",
     .why = "lit and shadowed swap on every surface the map sees"},
    {.name = "shadowmap-without-bias-matrix", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.no_bias_matrix = true; }), .convention = "gl",
     .scenes = "camera_in_shadow ground_sphere",
     .field_class = "the bias matrix left out (clip -1..1 read as texture coordinates)",
     .why = "clip coordinates -1..1 read as texture coordinates 0..1: three quarters of the view fall outside "
            "the map (lit) and the rest compares against the wrong texels and depths"},
    {.name = "reversed-z-compare-not-flipped", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.compare = CompareFault::ConventionIgnored; }), .convention = "reversed-z",
     .scenes = "ground_sphere",
     .field_class = "reversed-Z: the compare direction not flipped (GL_LEQUAL kept)",
     .why = "under reversed-Z nearer is greater: GL_LEQUAL calls the receivers behind an occluder lit and the "
            "lit ones shadowed"},
    {.name = "reversed-z-rgba8-compare-not-flipped", .technique = "shadowmap-rgba8",
     .faults = on([](Faults& f) { f.shadow_map.compare = CompareFault::ConventionIgnored; }), .convention = "reversed-z",
     .scenes = "ground_sphere",
     .field_class = "reversed-Z: the compare direction not flipped, in a shader's own compare (packed RGBA8 depth)",
     .why = "the same swap in the shader's own integer compare of packed depths"},
    {.name = "reversed-z-clear-to-one", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.clear_to_one = true; }), .convention = "reversed-z",
     .scenes = "ground_sphere",
     .field_class = "reversed-Z: the depth cleared to 1 instead of 0",
     .why = "1 is the near plane under reversed-Z: GL_GREATER never passes, the map keeps the near plane "
            "everywhere and every receiver lies behind it"},
    {.name = "reversed-z-offset-sign", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.offset_sign_ignored = true; }), .convention = "reversed-z",
     .scenes = "ground_sphere",
     .field_class = "reversed-Z: the bias / polygon-offset sign not flipped",
     .why = "the offset pulls depth toward the light instead of pushing it away: the two-sided ground, stored "
            "nearer than itself, shadows itself all over"},
    {.name = "zero-to-one-with-neg-one-bias", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.neg_one_to_one_bias = true; }), .convention = "gl-zo",
     .scenes = "ground_sphere",
     .field_class = "a -1..1 bias matrix (z -> 0.5 z + 0.5) on 0..1 depth",
     .why = "0.5 z + 0.5 moves every receiver's 0..1 depth halfway to the far plane, behind whatever the map "
            "stored there: nearly everything is shadowed"},
    {.name = "acne-no-offset", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.no_polygon_offset = true; }), .convention = "gl",
     .scenes = "directional_light grazing_light",
     .field_class = "shadow acne: no slope-scaled bias (polygon offset 0, 0)",
     .why = "the two-sided ground compares against its own depth, sampled at texel centres: without offset about "
            "half of its lit pixels find their own texel nearer the light, stripes of false shadow (worst under "
            "the sun 8 degrees up)"},
    {.name = "peter-panning", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.large_constant_offset = true; }), .convention = "gl",
     .scenes = "contact_shadow cornell_box",
     .field_class = "peter-panning: a large constant bias",
     .why = "the stored depth of the slab and the blocks is pushed so far back that the floor next to their "
            "bases compares as in front of them: the shadows come loose from the contact"},
    {.name = "shadowmap-casters-culled-to-view", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.cull_casters_outside_view = true; }), .convention = "gl",
     .scenes = "offscreen_caster skinned_offscreen",
     .field_class = "casters outside the view frustum culled from the shadow pass",
     .why = "the pole, and the posed character, stand out of the camera's view and cast long shadows across the visible "
            "ground"},
    {.name = "fit-near-too-tight", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.fit = FitFault::NearTooTight; }), .convention = "gl",
     .scenes = "ground_sphere",
     .field_class = "a light fit that clips casters (near plane too tight)",
     .why = "the near half of the light's depth range is clipped, and with it the sphere: its shadow vanishes"},
    {.name = "fit-far-too-tight", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.fit = FitFault::FarTooTight; }), .convention = "gl",
     .scenes = "contact_shadow torus_self_shadow",
     .field_class = "a light fit that clips casters (far plane too tight)",
     .why = "the far half of the light's depth range is clipped, and with it the lower part of the casters: the "
            "slab's shadow and the ring's shadow on the ground vanish"},
    {.name = "cube-z-faces-swapped", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.cube = CubeFault::ZFacesSwapped; }), .convention = "gl",
     .scenes = "cube_seams stairs_room",
     .field_class = "cube-map face seams: the wrong face picked (+z and -z exchanged)",
     .why = "the light among the casters needs a cube; the shadows that fall in its +z and -z faces are looked "
            "up in the opposite face's depths: they vanish or move"},
    {.name = "cube-y-faces-upside-down", .technique = "shadowmap-pcf",
     .faults = on([](Faults& f) { f.shadow_map.cube = CubeFault::YFacesUpsideDown; }), .convention = "gl",
     .scenes = "cube_seams ground_sphere stairs_room",
     .field_class = "cube-map face seams: a face's orientation wrong (the +y and -y faces turned)",
     .why = "each scene's point light needs a cube (geometry more than 80 degrees off any single view); the shadows "
            "under the light lie in the -y face, which, turned by 180 degrees, puts them on the opposite side of the "
            "light and breaks them where they cross into the side faces"},
    {.name = "half-texel-offset", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.half_texel_offset = true; }), .convention = "gl",
     .scenes = "light_near_caster",
     .field_class = "a half-texel offset (Direct3D 9 texel centres)",
     .why = "with maps of 128 texels, the light 0.4 above the plate opens its view to 160 degrees to hold the "
            "ground, so a texel at the shadow's outline covers several camera pixels: half a texel more moves "
            "the whole outline by a pixel or more, while the right technique's axis-aligned outline stays within "
            "a fraction of a texel (at the automatic size, 3 texels per camera pixel, half a texel is a sixth of "
            "a pixel and no scene tells it from the right technique's own texel quantisation, which the "
            "shadow-map threshold must allow)",
     .shadow_map_size = 128},
    // The classes new backends (WebGPU) break in their own ways: the texture origin and a light
    // direction's sign, each in the convention families it applies to. (An inverted cull in the
    // depth pass is no row: with this renderer's slope-scaled offset a front-face map is a right map,
    // PASS on every shadow-map scene; the class is acne only under a back-face map's small bias,
    // which acne-no-offset stands for.)
    {.name = "lookup-y-flipped", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.lookup_y_flipped = true; }), .convention = "gl",
     .scenes = "directional_light two_lights",
     .field_class = "the shadow coordinate's t read as 1 - t (a top-left texture origin taken for bottom-left)",
     .why = "every shadow is looked up mirrored in the light's view: the casters' shadows land on the far side "
            "of the light's view centre and the true shadows are lit"},
    {.name = "lookup-y-flipped-d3d", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.lookup_y_flipped = true; }), .convention = "d3d",
     .scenes = "directional_light two_lights",
     .field_class = "the shadow coordinate's t read as 1 - t, left-handed 0..1 depth",
     .why = "as in gl: the mirror is in the map's t, whatever the handedness and depth range of the light's projection"},
    {.name = "lookup-y-flipped-reversed-z", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.lookup_y_flipped = true; }), .convention = "reversed-z",
     .scenes = "directional_light two_lights",
     .field_class = "the shadow coordinate's t read as 1 - t, reversed-Z",
     .why = "as in gl: the mirror is in the map's t, whatever the depth compare's direction"},
    {.name = "light-direction-mirrored-x", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.light_direction_mirrored_x = true; }), .convention = "gl",
     .scenes = "directional_light torus_self_shadow",
     .field_class = "a directional light's shadow view built from its direction mirrored in x",
     .why = "the map is drawn and looked up from the mirrored sun: shadows fall toward the other side in x, the "
            "true ones come out lit, while the lighting still faces the true sun"},
    {.name = "light-direction-mirrored-x-d3d", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.light_direction_mirrored_x = true; }), .convention = "d3d",
     .scenes = "directional_light torus_self_shadow",
     .field_class = "a directional light's shadow view built from its direction mirrored in x, left-handed",
     .why = "as in gl: the mirror is of the world direction, whatever the view's handedness"},
    // Alpha-masked and single-sided casters (scene/alpha_mask.hpp; the catalogue's alpha_* and
    // single_sided_cards scenes).
    {.name = "alpha-ignored-in-depth-pass", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.alpha = renderer::AlphaFault::Ignored; }), .convention = "gl",
     .scenes = "alpha_cards alpha_fence",
     .field_class = "masked casters drawn solid into the depth pass (three.js before r132, WebGPU #31802)",
     .why = "every leaf card and the whole fence cast their full quads: the ground under the cards' and the "
            "fence's holes, lit in the reference, is shadowed"},
    {.name = "alpha-cutoff-fixed-at-half", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.alpha = renderer::AlphaFault::CutoffHalf; }), .convention = "gl",
     .scenes = "alpha_cards",
     .field_class = "the material's alpha cutoff ignored for a fixed 0.5 in the shadow pass (Godot #19752)",
     .why = "the 0.25 card loses its 127 ring (too light) and the 0.75 card keeps its 191 ring (too dark): each "
            "a band of texels several pixels wide"},
    {.name = "vertex-alpha-ignored", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.alpha = renderer::AlphaFault::VertexAlphaIgnored; }), .convention = "gl",
     .scenes = "alpha_vertex",
     .field_class = "vertex alpha ignored in the shadow pass (PlayCanvas #5115)",
     .why = "the card with vertex alpha alone casts its whole quad instead of its opaque half, and the fading "
            "leaf keeps the texels its vertex alpha clears"},
    {.name = "single-sided-cards-front-culled", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.cull_open_front_faces = true; }), .convention = "gl",
     .scenes = "single_sided_cards",
     .field_class = "open casters culled like closed ones in the depth pass (front faces culled)",
     .why = "both cards face the light with their front: culled, they are missing from the map and cast no "
            "shadow at all"},

    // Skinned casters (scene/skin.hpp; the catalogue's skinned_* scenes).
    {.name = "shadowmap-skin-bind-pose", .technique = "shadowmap",
     .faults = on([](Faults& f) { f.shadow_map.skin_bind_pose = true; }), .convention = "gl",
     .scenes = "skinned_character skinned_offscreen",
     .field_class = "a skinned caster drawn in its bind pose in the shadow pass (the skin applied to the camera's passes only)",
     .why = "the shadow is the T-pose's: the raised arm's and the bent leg's shadows fall where the straight limbs would "
            "be, and the character seen posed does not match its shadow"},

    // ---- cascaded shadow maps -----------------------------------------------------------------
    {.name = "csm-gap-between-cascades", .technique = "csm",
     .faults = on([](Faults& f) { f.cascade.gap = true; }), .convention = "gl",
     .scenes = "sun_horizon",
     .field_class = "a gap between cascades (the selection's splits and the fit's disagree)",
     .why = "each cascade is picked only for the first 85 % of its slice: a band of ground before every split "
            "falls in no cascade, and the long shadows that cross it are cut by a lit stripe"},
    {.name = "csm-caster-clipped-from-cascade", .technique = "csm",
     .faults = on([](Faults& f) { f.cascade.slice_depth_range = true; }), .convention = "gl",
     .scenes = "sun_horizon",
     .field_class = "a caster between the light and a cascade clipped from its depth range",
     .why = "each cascade's depth range is its slice's sphere alone: the wall outside the view and the tall "
            "casters stand outside the spheres of the cascades their shadows fall in, and those shadows vanish"},
    {.name = "csm-fitted-to-the-wrong-frustum", .technique = "csm-pcf",
     .faults = on([](Faults& f) { f.cascade.frustum_behind_camera = true; }), .convention = "gl",
     .scenes = "sun_horizon",
     .field_class = "cascades fitted to the wrong frustum (the other handedness's viewing axis)",
     .why = "the slices are fitted behind the eye while the selection uses the true depth: each window holds only "
            "what its sphere, centred behind the eye, reaches in front of it (the near ground, the middle of the "
            "far cascades, whose spheres are large), and the shadows farther out, the wall's at the left and the "
            "tips of the pole's and the sphere's, come out lit"},
    // ---- percentage-closer soft shadows ---------------------------------------------------------
    {.name = "pcss-blocker-search-reads-the-receiver", .technique = "pcss",
     .faults = on([](Faults& f) { f.soft.blocker_depth_from_receiver = true; }), .convention = "gl",
     .scenes = "soft_penumbra",
     .field_class = "a PCSS blocker search that returns the receiver's depth",
     .why = "the penumbra estimate (d_receiver - d_blocker) / d_blocker is 0: every soft shadow comes out hard, "
            "wrong by up to half the light across every penumbra"},
    {.name = "pcss-penumbra-for-half-the-light", .technique = "pcss",
     .faults = on([](Faults& f) { f.soft.light_size_scale = 0.5; }), .convention = "gl",
     .scenes = "soft_penumbra",
     .field_class = "a penumbra estimated with the wrong light size",
     .why = "the light's half-size taken for its size: every penumbra half as wide as the truth's, too dark in its "
            "outer half and too light in its inner half"},
    {.name = "pcss-penumbra-for-twice-the-light", .technique = "pcss",
     .faults = on([](Faults& f) { f.soft.light_size_scale = 2.0; }), .convention = "gl",
     .scenes = "soft_penumbra",
     .field_class = "a penumbra estimated with the wrong light size",
     .why = "the light's full size taken for its half-size: every penumbra twice as wide, the far ball's umbra "
            "gone"},
    {.name = "pcss-cube-taps-stay-in-face", .technique = "pcss",
     .faults = on([](Faults& f) { f.soft.taps_stay_in_face = true; }), .convention = "gl",
     .scenes = "soft_cube_seam",
     .field_class = "a cube map's filter taps confined to the fragment's own face (seams unfiltered)",
     .why = "the taps beyond the seam between the cube's downward and side faces read as unblocked: a line of "
            "light along the seam through the wall's shadow"},
    // ---- variance shadow maps over PCSS's penumbra -----------------------------------------------
    {.name = "vsm-blocker-search-reads-the-receiver", .technique = "vsm",
     .faults = on([](Faults& f) { f.soft.blocker_depth_from_receiver = true; }), .convention = "gl",
     .scenes = "soft_penumbra",
     .field_class = "a PCSS blocker search that returns the receiver's depth",
     .why = "the filter region shrinks to the receiver's own texels: the moments hold one depth and every soft "
            "shadow comes out hard"},
    {.name = "vsm-penumbra-for-twice-the-light", .technique = "vsm",
     .faults = on([](Faults& f) { f.soft.light_size_scale = 2.0; }), .convention = "gl",
     .scenes = "soft_penumbra",
     .field_class = "a penumbra estimated with the wrong light size",
     .why = "the moments averaged over twice the region: every penumbra twice as wide, the far ball's umbra gone"},
};
// clang-format on

}  // namespace

std::vector<std::string> Row::scene_list() const {
  std::vector<std::string> out;
  std::istringstream in{std::string(scenes)};
  for (std::string s; in >> s;) out.push_back(s);
  return out;
}

std::span<const Row> rows() { return kRows; }

std::vector<Control> controls() {
  // (technique, convention, map size) -> scenes
  std::map<std::tuple<std::string, std::string, int>, std::vector<std::string>> scenes;
  for (const Row& r : kRows) {
    auto& list = scenes[{std::string(r.technique), std::string(r.convention), r.shadow_map_size}];
    for (const std::string& s : r.scene_list()) list.push_back(s);
  }
  std::vector<Control> out;
  for (auto& [key, list] : scenes) {
    const auto& [technique, convention, size] = key;
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    std::string name = "control." + technique + "." + convention;
    if (size) name += ".map" + std::to_string(size);
    out.push_back(Control{name, technique, convention, size, list});
  }
  return out;
}

Control control_of(const Row& row) {
  for (Control& c : controls())
    if (c.technique == row.technique && c.convention == row.convention && c.shadow_map_size == row.shadow_map_size) return c;
  return {};  // unreachable: every row makes a control
}

}  // namespace shadowref::teeth
