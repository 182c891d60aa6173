// readme_test.cpp — the pack's README: the installed template filled from the technique table and the
// error classes, every placeholder known, every technique and every colour of the error image named.
#include <gtest/gtest.h>

#include <stdexcept>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/pack/readme.hpp"

namespace shadowref::pack {
namespace {

using nlohmann::json;

json two_scenes() {
  json m;
  const json metres = {{"symbol", "m"}, {"name", "metres"}, {"metres", 1.0}};
  const json millimetres = {{"symbol", "mm"}, {"name", "millimetres"}, {"metres", 0.001}};
  m["scenes"] = {{{"name", "a"}, {"description", "first"}, {"resolution", {64, 48}}, {"lights", 1}, {"units", metres},
                  {"size", 10.0}, {"light_clearance", {{{"distance", 1.0}, {"object", "ground"}}}}},
                 {{"name", "b"}, {"description", "second"}, {"resolution", {8, 8}}, {"lights", 3}, {"units", millimetres},
                  {"size", 1000.0},
                  {"light_clearance",
                   {nullptr, {{"distance", 0.1}, {"object", "ceiling"}}, {{"distance", 10.0}, {"object", "floor"}}}}}};
  return m;
}

TEST(Readme, TheTemplateFillsWithEveryTechniqueColourAndScene) {
  const std::string t = fill_readme(read_readme_template(SHADOWREF_README_TEMPLATE), two_scenes());
  EXPECT_EQ(t.rfind("# shadowref scene pack\n", 0), 0u) << "the template's leading comment is dropped";
  EXPECT_EQ(t.find("{{"), std::string::npos);
  // Every technique named in the "which technique" table.
  const std::size_t from = t.find("## Which technique name is my engine?");
  ASSERT_NE(from, std::string::npos);
  const std::string table = t.substr(from, t.find("\n## ", from + 1) - from);
  for (const outputs::TechniqueName& n : outputs::kTechniques)
    EXPECT_NE(table.find(" `" + std::string(n.name) + "` "), std::string::npos) << n.name;
  for (const outputs::ErrorClassRow& r : outputs::kErrorClasses)
    EXPECT_NE(t.find("| " + outputs::rgb_text(r.colour) + " " + std::string(r.colour_name) + " | " + std::string(r.legend) + " |\n"),
              std::string::npos)
        << r.name;
  // Each scene's units; a light nearer to a surface than kCloseLightShare of the scene's size (light 1
  // of b, 0.1 mm in 1000 mm) is said, one at 1 % or farther (b's light 2 at 10 mm, a's light) is not.
  EXPECT_NE(t.find("| a | 64x48 | 1 | metres | first |\n| b | 8x8 | 3 | millimetres | second. **Light 1 sits 0.1 mm from a "
                   "surface (ceiling)**: a shadow camera's near plane beyond that clips it. |\n"),
            std::string::npos);
  EXPECT_EQ(t.substr(t.size() - 2), "|\n");
}

TEST(Readme, PlaceholdersAreFilledFromTheTables) {
  EXPECT_EQ(fill_readme("x {{technique:csm-pcf}} y", json::object()), "x `csm-pcf` y");
  EXPECT_EQ(fill_readme("{{colour_name:acne}} {{json_key:acne}}", json::object()), "yellow unexplained_acne");
  const std::string names = fill_readme("{{technique_names}}", json::object());
  EXPECT_EQ(names.rfind("planar, volume-zpass, ", 0), 0u);
  EXPECT_EQ(names.substr(names.size() - 5), ", vsm");
  EXPECT_EQ(fill_readme("<!-- {{not filled}} -->\nkept", json::object()), "kept");
}

TEST(Readme, UnknownPlaceholdersAndNamesAreRefused) {
  EXPECT_THROW(fill_readme("{{techniques}}", json::object()), std::invalid_argument);
  EXPECT_THROW(fill_readme("{{technique:shadowmap-pcss}}", json::object()), std::invalid_argument);
  EXPECT_THROW(fill_readme("{{colour_name:glitter}}", json::object()), std::invalid_argument);
  EXPECT_THROW(fill_readme("{{json_key:undecided}}", json::object()), std::invalid_argument);
  EXPECT_THROW(fill_readme("open {{scenes", json::object()), std::invalid_argument);
  EXPECT_THROW(read_readme_template("/nonexistent/README.template.md"), std::runtime_error);
}

}  // namespace
}  // namespace shadowref::pack
