// shadowref/renderer/render_variants.hpp — the correct variants our renders may take, one row each.
//
// A correct variant is a RenderOptions field a user chooses (renderer.hpp says what each draws and
// declares). Its row here is everything else that names it: the command-line flag `shadowref render`
// and `shadowref conform` take it by (cmd/render_variant_options.cpp builds the options from these
// rows), the values it accepts, its help line, and the key report.json's "declarations" gives it
// under (conformance/conform). So a new correct variant of a shadow-map technique is three files: its
// field in renderer.hpp, its row in render_variants.cpp, and its use where the maps are drawn or
// declared (docs/architecture.md, "Where a correct variant goes").
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref::renderer {

struct RenderVariant {
  // The RenderOptions member the row sets: a number, a switch (a flag without a value) or one of
  // an enumeration's names (outputs::to_string's).
  using Field = std::variant<int RenderOptions::*, double RenderOptions::*, bool RenderOptions::*,
                             outputs::DepthFaces RenderOptions::*, outputs::StoredDepth RenderOptions::*>;
  std::string_view flag;  // "--random-taps"
  std::string_view key;   // report.json's "declarations" key: "random_taps"
  std::string_view help;  // the --help text
  Field field;
  // A number's accepted values: [min, max], or, where `problem` is set, the values it returns "" for
  // (its text otherwise ends the one line that names the flag), summarised by `accepts` in --help.
  double min = 0.0, max = 0.0;
  std::string (*problem)(long long value) = nullptr;
  std::string_view accepts;
};

// Every correct variant, in the order --help lists them.
std::span<const RenderVariant> render_variants();

// Copies each variant's field from `from` to `to`; the other fields of `to` are kept.
void copy_render_variants(const RenderOptions& from, RenderOptions& to);

// Every value of an enumeration field, in the order --help lists their names (outputs::to_string).
std::span<const outputs::DepthFaces> all_values(outputs::DepthFaces);
std::span<const outputs::StoredDepth> all_values(outputs::StoredDepth);

}  // namespace shadowref::renderer
