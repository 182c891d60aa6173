// shadowref/outputs/candidate.hpp — candidate.json: who made a folder of masks, and with what.
//
// Written beside the masks by every producer (our renderer writes it; an engine team writes its
// own), read by the judge: the declaration feeds the tolerance model (docs/tolerance-model.md),
// which explains a wrong pixel only by causes the declared technique and settings can have.
//
//   {
//     "producer": "my-engine",            string: the engine or tool
//     "version": "4.2.1",                 string
//     "technique": "shadowmap",           string: how it is judged (outputs/techniques.hpp), or any name
//     "convention": "gl",                 string: gl | gl-zo | reversed-z | d3d (mathlib/convention.hpp)
//     "shadow_map_size": 2048,            integer in [16, 16384], texels per side; 0 = "automatic" (ours)
//     "filter_radius_texels": 1,          number >= 0: how far the filter reaches beyond the centre
//                                         texel (0 one tap, 1 a 3x3 PCF box, ...)
//     "slope_bias_texels": 2,             number >= 0: slope-scaled bias, as the depth change of the
//                                         surface across this many texels (glPolygonOffset's factor)
//     "constant_bias": 0.0,               number >= 0: constant bias, in world units along the light ray
//     "light_views": "own",               "pack": the shadow maps use the pack's light view and
//                                         projection matrices (matrices.json), so their texel grid is
//                                         known; "own": the engine fits its own (grid phase unknown);
//                                         "declared": the engine's own, given in `views`
//     "views": [ {"view": [16], "projection": [16]} ],
//                                         "declared" only, per light: the engine's light views, each
//                                         its view (scene → light view) and projection (light view →
//                                         clip in the declared convention), 16 numbers column-major.
//                                         One view; six for a point light's cube (+x, −x, +y, −y, +z,
//                                         −z of scene space: the face a point's major axis picks); one
//                                         per cascade for a cascaded directional light, with
//     "cascade_splits": [0.1, 4, 12, 40]  "declared" cascades: the camera depths (world units along the
//                                         camera's view axis) where each cascade begins and ends, one
//                                         more than the views: cascade i decides [splits[i], splits[i+1])
//     "cascade_blend": 0.1                number in [0, 1): "declared" cascades, the fraction of each
//                                         cascade's depth range, at its far end, over which its shadow
//                                         is blended into the next cascade's (Babylon.js's
//                                         cascadeBlendPercentage); 0 = a hard switch at each split
//     "cascades": 4                       integer in [0, 8]: cascaded techniques (csm, csm-pcf), the
//                                         cascades per directional light, split as the pack's
//                                         `cascades` say; 0 = the pack's count
//     "light_taps": 8,                    integer in [1, 64]: soft techniques (pcss, vsm), the taps per axis
//                                         of the filter over the light's area: its fraction moves in
//                                         steps of about 1 / light_taps across a boundary (the
//                                         visibility judgement's sampling tolerance)
//     "sampling": "grid",                 "grid" | "random": how the filter places its taps. "grid": a
//                                         fixed stratified kernel (light_taps x light_taps over the
//                                         light, or the PCF box); "random": light_taps² taps placed
//                                         anew per pixel (a disk rotated by noise, jittered taps), whose
//                                         fraction is judged against a random estimator's spread
//     "normal_offset": 0.0,               number >= 0: normal-offset bias in world units (the lookup
//                                         point moved along the surface normal; three.js and Babylon
//                                         `normalBias`, Unity, Unreal)
//     "normal_offset_texels": 0.0,        number >= 0: the same in texels of the map at the point
//     "depth_bias": 0.0,                  number >= 0: a constant bias in the light projection's window
//                                         depth (0..1 over its near..far; three.js and Babylon `bias`,
//                                         as a magnitude); the judge converts it with the light view
//     "depth_faces": "back",              "front" | "back" | "both": the faces the depth pass draws
//     "depth": "window",                  "window": the maps store the light projection's window depth
//                                         (a depth texture); "distance": they store the distance from
//                                         the light over a range (a point light's cube written with
//                                         gl_FragDepth or a colour: three.js and Babylon point lights),
//                                         where glPolygonOffset does not apply and depth_bias is in
//                                         units of that range
//     "depth_range": 0.0,                 number > 0, world units: "distance" maps' range (far - near of
//                                         the shadow camera); needed with "distance" and a depth_bias
//     "environment": {                    where the render came from, recorded, shown per case and
//       "api": "webgpu",                  matched by an expectations line limited to it (docs/ci.md):
//       "adapter": "google swiftshader",  the graphics API (webgpu, webgl2, opengl, vulkan, d3d12,
//       "browser": "Chrome/156.0",        metal...), the adapter or driver as the engine reports it,
//       "engine": "three.js r187"         the browser and the engine; strings, never judged. Any
//     },                                  other key is refused (one list: kEnvironmentKeys)
//     "settings": { ... },                any JSON object: the engine's own settings (shadow camera,
//                                         caster faces, far distance...), recorded in report.json and
//                                         the HTML and never judged
//     "lights": [ {...}, {...} ]          one object per light, in the pack's light order (fewer: the
//                                         rest take the top level): each overrides the top-level
//                                         keys for its light — every key above but producer, version,
//                                         technique, convention and settings (engines size, bias and
//                                         filter each light's shadow apart)
//   }
// Every bias key (slope_bias_texels, constant_bias, normal_offset*, depth_bias) may only narrow what
// is explained: the judge explains false light by bias only up to what a correct map at the declared
// texel size needs there, and false shadow never by the receiver's own surface (docs/tolerance-model.md).
// Every key is optional. Absent keys take the defaults below (for a known technique: its family's
// defaults), and `defaulted` lists them, so the report can say which values were assumed.
// Unknown keys (the message points to "settings"), wrong types and values out of range are
// InputError(BadInput) naming the file and key.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace shadowref::outputs {

// The most light_taps a declaration may give.
inline constexpr int kMaxLightTaps = 64;

inline constexpr const char* kCandidateFile = "candidate.json";

// Every key candidate.json may hold, the one list (the reader, `defaulted`, the pack README's table).
inline constexpr std::array<const char*, 25> kCandidateKeys{
    "producer",          "version",       "technique",   "convention", "environment", "shadow_map_size",
    "atlas_tile",        "filter_radius_texels", "slope_bias_texels", "constant_bias", "light_views",
    "views",             "cascade_splits", "cascade_blend",
    "cascades",          "light_taps",    "sampling",    "normal_offset", "normal_offset_texels",
    "depth_bias",        "depth_faces",   "depth",       "depth_range", "settings",    "lights"};

// The keys of "environment", the one list (the reader, the report, expectations lines).
inline constexpr std::array<const char*, 4> kEnvironmentKeys{"api", "adapter", "browser", "engine"};

// Where a render came from: {key of kEnvironmentKeys, value} in kEnvironmentKeys' order, the keys given only.
using Environment = std::vector<std::pair<std::string, std::string>>;

// "api webgpu · adapter google swiftshader · …": an environment in one line of text ("" when empty).
std::string environment_text(const Environment& environment);

// The most `lights` entries a declaration may give (a scene's lights are far fewer).
inline constexpr std::size_t kMaxDeclaredLights = 64;

// The most views one light may declare (a cube's six, or up to kMaxCascades cascades).
inline constexpr std::size_t kMaxDeclaredViews = 8;

// How the judge knows the light views of the candidate's maps.
enum class LightViews {
  Own,       // "own": the engine fits its own; the grid's turn and phase are unknown (a whole texel)
  Pack,      // "pack": the pack's matrices.json views at the declared map size (half a texel)
  Declared,  // "declared": the engine's own, given in `views` (half a texel, as the pack's)
};
const char* to_string(LightViews v);  // "own", "pack", "declared"

// One light view a candidate declares: view (scene → light view space) and projection (light view
// → clip space, in the declaration's convention: its depth range and handedness), each 16 numbers
// column-major (element [4 c + r] is row r, column c: glTF, three.js's Matrix4.elements, OpenGL's
// glUniformMatrix4fv without transpose).
struct DeclaredView {
  std::array<double, 16> view{}, projection{};
};

// The faces a depth pass draws.
enum class DepthFaces { Front, Back, Both };
const char* to_string(DepthFaces f);  // "front", "back", "both"
std::optional<DepthFaces> depth_faces_from(std::string_view name);  // to_string's inverse; nullopt otherwise

// What a shadow map stores: the light projection's window depth, or the distance from the light.
enum class StoredDepth { Window, Distance };
const char* to_string(StoredDepth d);  // "window", "distance"

// How a filter places its taps: a fixed stratified grid, or anew per pixel at random.
enum class Sampling { Grid, Random };
const char* to_string(Sampling s);  // "grid", "random"

struct CandidateDeclaration {
  std::string producer = "unknown";
  std::string version = "unknown";
  std::string technique;               // empty: the technique the judge was asked for
  std::string convention = "gl";
  int shadow_map_size = 0;             // 0: automatic (the fit of mathlib/light_fit.hpp)
  // "atlas_tile": {"size": T, "guard_band": G}: the light's map is a T x T tile of a shadow atlas
  // whose G texels along each side are a guard band beyond the view (filter taps at the view's edge
  // stay in the tile). The view spans T - 2G texels, and that is its map size: shadow_map_size is
  // set to it (giving both keys is refused). 0: not an atlas tile.
  int atlas_tile_size = 0;
  int atlas_guard_band = 0;
  double filter_radius_texels = 0.0;   // shadowmap-pcf's default: 1 (3 × 3)
  double slope_bias_texels = 2.0;      // our renderer's glPolygonOffset factor (its PCF maps: 3)
  double constant_bias = 0.0;
  LightViews light_views = LightViews::Own;
  std::vector<DeclaredView> views;     // "declared": this light's views (see above)
  std::vector<double> cascade_splits;  // "declared" cascades: camera depths, one more than the views
  double cascade_blend = 0.0;          // "declared" cascades: the blended share of each cascade's far end
  int cascades = 0;                    // cascaded techniques: cascades per directional light; 0: the pack's default
  int light_taps = 8;                  // soft techniques: filter taps per axis over the light (ours: 8 x 8)
  Sampling sampling = Sampling::Grid;  // "random": light_taps² taps placed anew per pixel
  double normal_offset = 0.0;          // world units along the surface normal
  double normal_offset_texels = 0.0;   // texels of the map at the point, along the surface normal
  double depth_bias = 0.0;             // window depth of the light's projection (0..1 over near..far)
  DepthFaces depth_faces = DepthFaces::Back;  // ours: front faces culled (back faces drawn)
  StoredDepth depth = StoredDepth::Window;    // Distance: depth_bias is in units of depth_range
  double depth_range = 0.0;                   // world units, the distance maps' far - near
  Environment environment;             // "environment": recorded, shown, matched by expectations lines
  std::string settings_json = "{}";    // "settings", as compact JSON text: recorded, never judged
  std::vector<std::string> defaulted;  // keys that were absent
  // "lights": per light (the pack's order), this declaration with that entry's overrides; empty:
  // every light takes this one. The judge refuses more entries than the scene has lights.
  std::vector<CandidateDeclaration> lights;

  // The declaration of light `light`: its `lights` entry, or this one.
  const CandidateDeclaration& for_light(std::size_t light) const;
};

// The defaults for `technique` (its family's filter), every key marked defaulted.
CandidateDeclaration default_declaration(const std::string& technique);

// Reads `dir`/candidate.json; a missing file gives default_declaration(technique). Throws
// InputError(BadInput) for a malformed file.
CandidateDeclaration read_declaration(const std::filesystem::path& dir, const std::string& technique);

// The declaration that the JSON object `j` (candidate.json's shape) states, read as read_declaration
// reads a file: the same keys, ranges and per-light rules, `defaulted` the keys `j` lacks. A report's
// "candidate" (declaration_text's object) reads back as the declaration it was written from. Throws
// InputError(BadInput) "`where`: what is wrong".
CandidateDeclaration declaration_from_json(const nlohmann::json& j, const std::string& technique, const std::string& where);

// `declaration` as candidate.json's text (without `defaulted`): every key, the one writer.
std::string declaration_text(const CandidateDeclaration& declaration);

// Writes `declaration` as `dir`/candidate.json (declaration_text). Throws FileError.
void write_declaration(const CandidateDeclaration& declaration, const std::filesystem::path& dir);

}  // namespace shadowref::outputs
