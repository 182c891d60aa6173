// identifier_test.cpp — the safe-identifier rule (shadowref/scene/identifier.hpp): what it
// accepts, what it refuses, and the first problem it names.
#include "shadowref/scene/identifier.hpp"

#include <gtest/gtest.h>

#include <string>

namespace shadowref::scene {
namespace {

TEST(Identifier, AcceptsTheCatalogueKindOfName) {
  using namespace std::string_literals;
  for (const std::string& name : {"a"s, "Z"s, "0"s, "ground_sphere"s, "nested_256_volumes"s, "v1.2-final"s, "a.b.c"s, "x-"s,
                                  "x_"s, "x."s, std::string(64, 'a')}) {
    EXPECT_TRUE(is_safe_identifier(name)) << name;
    EXPECT_EQ(identifier_problem(name), std::nullopt) << name;
  }
}

TEST(Identifier, RefusesEverythingThatIsNotOneEntryOfAFolder) {
  using namespace std::string_literals;
  for (const std::string& name : {""s, std::string(65, 'a'), "."s, ".."s, "../x"s, "x/.."s, "a..b"s, ".hidden"s, "-x"s, "_x"s,
                                  "a/b"s, "/abs"s, "a\\b"s, "C:evil"s, "c:"s, "a b"s, "tab\there"s, "new\nline"s,
                                  "nul\0byte"s, "caf\xc3\xa9"s, "star*"s, "q?"s, "<a>"s, "a|b"s, "\"q\""s}) {
    EXPECT_FALSE(is_safe_identifier(name)) << name;
    ASSERT_TRUE(identifier_problem(name).has_value()) << name;
    EXPECT_EQ(identifier_problem(name)->find('\n'), std::string::npos) << "one line: " << *identifier_problem(name);
  }
}

TEST(Identifier, NamesTheFirstProblem) {
  const auto problem = [](std::string_view name) {
    const auto p = identifier_problem(name);
    return p ? p->substr(0, p->find(" (a name becomes")) : std::string("none");
  };
  EXPECT_EQ(problem(""), "must not be empty");
  EXPECT_EQ(problem(std::string(65, 'a')), "must be at most 64 characters, not 65");
  EXPECT_EQ(problem("../../escaped_scene"), "must not contain '..'");
  EXPECT_EQ(problem(".hidden"), "must start with a letter or a digit, not '.'");
  EXPECT_EQ(problem("a/b"), "must not contain '/'");
  EXPECT_EQ(problem("C:evil"), "must not contain ':'");
  EXPECT_EQ(problem(std::string_view("a\0b", 3)), "must not contain byte 0x00");
  EXPECT_EQ(problem("x\n"), "must not contain byte 0x0A");
  // Every refusal carries the rule itself, so that one message says how to fix the name.
  EXPECT_NE(identifier_problem("a/b")->find("1 to 64 of A-Z a-z 0-9 _ . -, starting with a letter or a digit, no '..'"),
            std::string::npos);
}

}  // namespace
}  // namespace shadowref::scene
