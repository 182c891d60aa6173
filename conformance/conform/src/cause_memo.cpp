// cause_memo.cpp — the judge's memo of the cause model's answers (cause_memo.hpp).
#include "cause_memo.hpp"

#include <cstdlib>
#include <new>

namespace shadowref::conform {

void CauseMemo::Table::FreeBytes::operator()(std::uint8_t* p) const { std::free(p); }

CauseMemo::Table::Table(std::size_t lights, int width, int height)
    : width_(width), height_(height), bytes_(lights * static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  for (std::size_t i = 0; i < lights; ++i) {
    // calloc: fresh zero pages, touched only where a boundary pixel is remembered.
    auto* p = static_cast<std::uint8_t*>(std::calloc(n > 0 ? n : 1, 1));
    if (!p) throw std::bad_alloc();
    lights_.emplace_back(p);
  }
}

std::uint8_t* CauseMemo::Table::slot(std::size_t light, int x, int y) const {
  if (light >= lights_.size() || x < 0 || y < 0 || x >= width_ || y >= height_) return nullptr;
  return lights_[light].get() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
}

bool CauseMemo::Table::find(std::size_t light, int x, int y, bool candidate_lit, outputs::Cause& cause) const {
  const std::uint8_t* s = slot(light, x, y);
  if (!s) return false;
  const std::uint8_t v = candidate_lit ? *s >> 4 : *s & 0x0F;
  if (v == 0) return false;
  cause = static_cast<outputs::Cause>(v - 1);
  return true;
}

void CauseMemo::Table::remember(std::size_t light, int x, int y, bool candidate_lit, outputs::Cause cause) {
  std::uint8_t* s = slot(light, x, y);
  if (!s) return;  // outside the scene's image: asked of the model each time
  const auto v = static_cast<std::uint8_t>(static_cast<std::uint8_t>(cause) + 1);
  *s = candidate_lit ? static_cast<std::uint8_t>((*s & 0x0F) | (v << 4)) : static_cast<std::uint8_t>((*s & 0xF0) | v);
}

CauseMemo::Table& CauseMemo::table(const scene::PreparedScene& prepared, const std::string& key) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it)
    if (it->prepared == &prepared && it->key == key) {
      entries_.splice(entries_.begin(), entries_, it);
      return entries_.front().table;
    }
  const scene::Scene& s = *prepared.scene;
  entries_.push_front({&prepared, key, Table(s.lights.size(), s.width, s.height)});
  bytes_ += entries_.front().table.bytes();
  // The newest table always stays, whatever its size.
  while (bytes_ > kBudgetBytes && entries_.size() > 1) {
    bytes_ -= entries_.back().table.bytes();
    entries_.pop_back();
  }
  return entries_.front().table;
}

}  // namespace shadowref::conform
