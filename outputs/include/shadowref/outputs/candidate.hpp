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
//                                         known; "own": the engine fits its own (grid phase unknown)
//     "cascades": 4                       integer in [0, 8]: cascaded techniques (csm, csm-pcf), the
//                                         cascades per directional light, split as the pack's
//                                         `cascades` say; 0 = the pack's count
//     "light_taps": 8                     integer in [1, 64]: soft techniques (pcss, vsm), the taps per axis
//                                         of the filter over the light's area: its fraction moves in
//                                         steps of about 1 / light_taps across a boundary (the
//                                         visibility judgement's sampling tolerance)
//   }
// Every key is optional. Absent keys take the defaults below (for a known technique: its family's
// defaults), and `defaulted` lists them, so the report can say which values were assumed.
// Unknown keys, wrong types and values out of range are InputError(BadInput) naming the file and key.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shadowref::outputs {

// The most light_taps a declaration may give.
inline constexpr int kMaxLightTaps = 64;

inline constexpr const char* kCandidateFile = "candidate.json";

struct CandidateDeclaration {
  std::string producer = "unknown";
  std::string version = "unknown";
  std::string technique;               // empty: the technique the judge was asked for
  std::string convention = "gl";
  int shadow_map_size = 0;             // 0: automatic (the fit of mathlib/light_fit.hpp)
  double filter_radius_texels = 0.0;   // shadowmap-pcf's default: 1 (3 × 3)
  double slope_bias_texels = 2.0;      // our renderer's glPolygonOffset factor (its PCF maps: 3)
  double constant_bias = 0.0;
  bool light_views_from_pack = false;  // "light_views": "pack"
  int cascades = 0;                    // cascaded techniques: cascades per directional light; 0: the pack's default
  int light_taps = 8;                  // soft techniques: filter taps per axis over the light (ours: 8 x 8)
  std::vector<std::string> defaulted;  // keys that were absent
};

// The defaults for `technique` (its family's filter), every key marked defaulted.
CandidateDeclaration default_declaration(const std::string& technique);

// Reads `dir`/candidate.json; a missing file gives default_declaration(technique). Throws
// InputError(BadInput) for a malformed file.
CandidateDeclaration read_declaration(const std::filesystem::path& dir, const std::string& technique);

// Writes `declaration` as `dir`/candidate.json (without `defaulted`). Throws FileError.
void write_declaration(const CandidateDeclaration& declaration, const std::filesystem::path& dir);

}  // namespace shadowref::outputs
