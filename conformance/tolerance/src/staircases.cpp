// staircases.cpp — a declared map size against the candidate's staircases on the pack's grid
// (staircases.hpp).
#include "shadowref/tolerance/staircases.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <unordered_map>

#include "shadowref/reference/causes.hpp"

namespace shadowref::tolerance {
using Cell = reference::CauseModel::TexelCell;

bool staircases_apply(const outputs::CandidateDeclaration& d) {
  return d.light_views != outputs::LightViews::Own && d.shadow_map_size > 0 && d.filter_radius_texels == 0 &&
         d.sampling == outputs::Sampling::Grid && d.normal_offset == 0 && d.normal_offset_texels == 0;
}

StaircaseCheck check_staircases(const reference::CauseModel& model, const outputs::Image8& mask, std::size_t light,
                                const outputs::CandidateDeclaration& d) {
  const int w = mask.width, h = mask.height;
  const auto at = [&](int x, int y) { return mask.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]; };
  // Each pixel's cell, traced once and only beside a candidate boundary: a few thousand pixels of a
  // mask, so kept by index rather than in an image-sized table.
  std::unordered_map<std::size_t, std::optional<Cell>> cells;
  const auto cell = [&](int x, int y) -> const std::optional<Cell>& {
    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
    auto [it, added] = cells.try_emplace(i);
    if (added) it->second = model.texel_cell(light, x, y, d);
    return it->second;
  };
  StaircaseCheck c;
  const auto pair = [&](int ax, int ay, int bx, int by) {
    const std::uint8_t a = outputs::mask_class(at(ax, ay)), b = outputs::mask_class(at(bx, by));
    const bool crossing = (a == outputs::kClassLit && b == outputs::kClassShadowed) ||
                          (a == outputs::kClassShadowed && b == outputs::kClassLit);
    if (!crossing) return;
    const std::optional<Cell>& ca = cell(ax, ay);
    const std::optional<Cell>& cb = cell(bx, by);
    if (!ca || !cb || ca->view != cb->view || !ca->shares_plane(*cb)) return;
    ++c.crossings;
    c.in_one_texel += ca->column == cb->column && ca->row == cb->row;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) pair(x, y, x + 1, y);
      if (y + 1 < h) pair(x, y, x, y + 1);
    }
  c.contradicted = c.crossings >= kMinStaircaseCrossings && 2 * c.in_one_texel > c.crossings;
  return c;
}

std::string describe(const StaircaseCheck& c, std::size_t light, const outputs::CandidateDeclaration& d) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "light %zu: the declared %d-texel map on %s %s by the candidate's staircases (%zu of %zu "
                "lit/shadowed crossings on one receiver lie inside one texel)%s",
                light, d.shadow_map_size,
                d.light_views == outputs::LightViews::Declared ? "the declared light matrices' grid" : "the pack's grid",
                c.contradicted ? "is contradicted" : "is not contradicted", c.in_one_texel, c.crossings,
                c.contradicted ? (d.light_views == outputs::LightViews::Declared
                                      ? ": its texels are judged as the candidate's own views at that size"
                                      : ": its texels are judged at the automatic size")
                               : "");
  return buf;
}

}  // namespace shadowref::tolerance
