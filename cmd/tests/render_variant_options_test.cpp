// render_variant_options_test.cpp — the correct variants' command line, built from the renderer's
// table (render_variants.hpp): each row's flag sets its own field and no other, each refuses what
// its row refuses with a line that names the value, and the table names each flag and key once.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <set>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "render_variant_options.hpp"

#include "command.hpp"
#include "shadowref/renderer/render_variants.hpp"

namespace shadowref::cli {
namespace {

using renderer::RenderOptions;
using renderer::RenderVariant;

// The arguments that give row `v` a value other than RenderOptions' default.
std::vector<std::string> non_default_arguments(const RenderVariant& v) {
  std::vector<std::string> args{std::string(v.flag)};
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(RenderOptions{}.*member)>;
        if constexpr (std::is_same_v<T, bool>) {
          // a flag: no value
        } else if constexpr (std::is_enum_v<T>) {
          args.emplace_back(outputs::to_string(renderer::all_values(T{}).back()));
        } else if (v.problem) {
          args.emplace_back("16");
        } else {
          args.emplace_back(std::to_string(static_cast<T>(v.max)));
        }
      },
      v.field);
  return args;
}

// Whether row `v`'s field holds the same value in `a` and `b`.
bool same_field(const RenderVariant& v, const RenderOptions& a, const RenderOptions& b) {
  return std::visit([&](auto member) { return a.*member == b.*member; }, v.field);
}

void parse(CLI::App& app, std::vector<std::string> args) {
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  app.parse(reversed);
}

TEST(RenderVariantOptions, EachFlagSetsItsOwnFieldAndNoOther) {
  const RenderOptions defaults;
  for (const RenderVariant& v : renderer::render_variants()) {
    CLI::App app;
    RenderVariantArgs args;
    add_render_variant_options(app, args);
    parse(app, non_default_arguments(v));
    RenderOptions applied;
    applied.shadow_map_size = 512;
    apply_render_variants(args, 512, applied);
    EXPECT_EQ(applied.shadow_map_size, 512) << v.flag << ": a field outside the table changed";
    for (const RenderVariant& w : renderer::render_variants())
      EXPECT_EQ(same_field(w, applied, defaults), &w != &v) << v.flag << " and " << w.flag;
  }
}

TEST(RenderVariantOptions, RefusedValuesNameTheValueAndWhatIsAccepted) {
  const auto refusal = [](std::vector<std::string> args) -> std::string {
    CLI::App app;
    RenderVariantArgs variants;
    add_render_variant_options(app, variants);
    try {
      parse(app, args);
    } catch (const CLI::ParseError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(refusal({"--random-taps", "5"}).find("5: must be one of 0, 4, 9, 16"), std::string::npos)
      << refusal({"--random-taps", "5"});
  EXPECT_NE(refusal({"--random-taps", "four"}).find("four: not a whole number"), std::string::npos);
  EXPECT_NE(refusal({"--depth-faces", "sideways"}).find("sideways"), std::string::npos);
  EXPECT_NE(refusal({"--guard-band", "65"}).find("65"), std::string::npos);
  EXPECT_NE(refusal({"--view-turn", "91"}).find("91"), std::string::npos);
  EXPECT_EQ(refusal({"--random-taps", "64", "--cube-depth", "distance", "--view-phase", "1"}), "");
}

TEST(RenderVariantOptions, AGuardBandThatOverflowsTheMapIsBadInput) {
  CLI::App app;
  RenderVariantArgs args;
  add_render_variant_options(app, args);
  parse(app, {"--guard-band", "8"});
  RenderOptions o;
  EXPECT_THROW(apply_render_variants(args, 16384, o), BadInput);
  EXPECT_NO_THROW(apply_render_variants(args, 16384 - 16, o));
  EXPECT_EQ(o.guard_band_texels, 8);
}

TEST(RenderVariantOptions, TheTableNamesEachFlagAndKeyOnce) {
  std::set<std::string_view> flags, keys;
  for (const RenderVariant& v : renderer::render_variants()) {
    EXPECT_TRUE(flags.insert(v.flag).second) << v.flag;
    EXPECT_TRUE(keys.insert(v.key).second) << v.key;
    EXPECT_FALSE(v.help.empty()) << v.flag;
  }
}

}  // namespace
}  // namespace shadowref::cli
