// cause_memo.hpp — the cause model's answers per pixel, kept for the judge's later questions under
// the same declaration: an exact memo, since CauseModel::explain's answer depends only on the
// light, the pixel, the candidate's answer there and the declaration (never on an earlier call).
//
// Why: a case's comparison, its resolving power's 21 probes (each a comparison of a shifted, grown
// or tiled copy of the reference) and a grid's mutants under one declaration ask about the same
// boundary pixels over and over; the probes of a 256² case alone ask some five times as many
// questions as there are distinct pixels along its boundaries, each question up to 128 rays.
//
// Storage: one byte per pixel and light (a nibble per candidate answer: 0 unknown, else the cause
// + 1) in calloc'd pages, so that a table costs only the pages its boundary pixels touch; tables
// are kept per (prepared scene, declaration key), the oldest dropped past a byte budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <string>
#include <vector>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::conform {

class CauseMemo {
 public:
  // One declaration's answers on one scene: `lights` tables of width × height pixels.
  class Table {
   public:
    Table(std::size_t lights, int width, int height);
    // The remembered cause of (light, x, y, candidate_lit), or false.
    bool find(std::size_t light, int x, int y, bool candidate_lit, outputs::Cause& cause) const;
    void remember(std::size_t light, int x, int y, bool candidate_lit, outputs::Cause cause);
    std::size_t bytes() const { return bytes_; }

   private:
    struct FreeBytes {
      void operator()(std::uint8_t* p) const;
    };
    std::uint8_t* slot(std::size_t light, int x, int y) const;
    int width_, height_;
    std::size_t bytes_;
    std::vector<std::unique_ptr<std::uint8_t[], FreeBytes>> lights_;
  };

  // The table of `prepared` under declaration `key`, made empty when first asked for. Tables past
  // kBudgetBytes (their full sizes, the oldest first) are dropped: a dropped table's answers are
  // asked of the model again, the same answers.
  Table& table(const scene::PreparedScene& prepared, const std::string& key);

  // About 32 tables of a two-light 1080p scene; a 256² run keeps every case's.
  static constexpr std::size_t kBudgetBytes = std::size_t{128} << 20;

 private:
  struct Entry {
    const scene::PreparedScene* prepared;
    std::string key;
    Table table;
  };
  std::list<Entry> entries_;  // the most recently asked for first
  std::size_t bytes_ = 0;
};

}  // namespace shadowref::conform
