// shadowref/tolerance/staircases.hpp — a declared map size checked against the candidate's own
// staircases, where the judge knows the texel grid: the pack's light views, or declared matrices.
//
// A hard shadow map answers per texel: every point of one texel reads the same stored depth, so on
// one receiver a nearest lookup's lit/shadowed boundaries run between texels. Where the candidate
// declares `"light_views": "pack"` (or `"declared"`, the engine's own matrices) and a
// `shadow_map_size`, the grid is that view at that size
// (reference/causes.hpp, texel_cell), and the judge counts the candidate's own crossings — two
// 4-adjacent pixels whose surface points lie on one receiver plane, both facing the light, one lit
// and one shadowed — and of those the ones whose two points lie in one texel. A correct render has
// such crossings only where the comparison itself flips inside a texel (a caster touching the
// receiver), a few; a render drawn with a finer map than declared, or a fine boundary moved by a
// pixel, has them wherever the declared texel is wider than a pixel. When more than half of them
// lie in one texel the declared size is contradicted, and that light's texels are judged at the
// automatic size, as if no size had been declared: what the pixels show, not what was said. The
// case's causes say so, with the counts (docs/tolerance-model.md, "What a declaration may do").
//
// Checked for hard lookups only — the shadow-map family with no filter, a grid kernel and no normal
// offset: a filter's boundary is its threshold's, not the texels', and a normal offset moves the
// lookup off the point. Cost: one primary ray per pixel beside a candidate boundary.
#pragma once

#include <cstddef>
#include <string>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/image.hpp"

namespace shadowref::reference {
class CauseModel;
}

namespace shadowref::tolerance {

struct StaircaseCheck {
  std::size_t crossings = 0;     // lit/shadowed 4-neighbour pairs on one receiver plane, both facing the light
  std::size_t in_one_texel = 0;  // of those, both points in one texel of the declared map
  bool contradicted = false;     // at least kMinStaircaseCrossings, more than half of them in one texel
};

// Fewer crossings than this say nothing either way (a shadow a few pixels long).
inline constexpr std::size_t kMinStaircaseCrossings = 32;

// Whether a light's declaration is checked: pack views, a size given, a hard unfiltered lookup.
bool staircases_apply(const outputs::CandidateDeclaration& light_declaration);

// The check of light `light`'s candidate mask (the scene's resolution, rows from the top) under its
// declaration.
StaircaseCheck check_staircases(const reference::CauseModel& model, const outputs::Image8& mask, std::size_t light,
                                const outputs::CandidateDeclaration& light_declaration);

// The check in words, for the case's causes: "light 0: ...".
std::string describe(const StaircaseCheck& check, std::size_t light, const outputs::CandidateDeclaration& light_declaration);

}  // namespace shadowref::tolerance
