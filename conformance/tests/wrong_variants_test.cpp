// wrong_variants_test.cpp — the suite's teeth: every deliberately wrong technique
// (wrong_variants/) is run through the very conformance run users get (run_conform: cached
// references, renders, comparisons, catalogue expectations) on the default catalogue, and must be
// a FAIL on at least one scene. A variant that passes everywhere means a threshold or the
// catalogue is too weak to tell a known bug from the truth.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/conform.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "wrong_variants.hpp"

namespace shadowref {
namespace {

TEST(WrongVariants, EachIsCaughtAsFailOnAtLeastOneCatalogueScene) {
  conform::ConformOptions o;
  o.scenes = conform::select_scenes(conform::default_catalogue(), {});
  for (const wrong::WrongVariant& v : wrong::wrong_variants()) {
    o.extra_techniques.push_back({&v.technique, v.judged_as});
    o.techniques.emplace_back(v.technique.name);
  }
  // The right techniques the variants pretend to be, on the same scenes: a catch counts only where
  // the right one passes (else the scene, not the bug, made it fail).
  for (const wrong::WrongVariant& v : wrong::wrong_variants())
    if (renderer::find_technique(v.judged_as)) o.techniques.emplace_back(v.judged_as);
  o.backend = "llvmpipe";
  o.out = SHADOWREF_TEST_OUT;
  o.cache = SHADOWREF_TEST_CACHE;
  const conform::ConformResult r = conform::run_conform(o);
  std::printf("%s\nreport: %s\n", conform::table_text(r).c_str(), r.report_html.string().c_str());

  for (const wrong::WrongVariant& v : wrong::wrong_variants()) {
    const std::string name(v.technique.name);
    std::string caught, errors;
    std::map<std::string, conform::Status> right;  // scene -> the right technique's status
    for (const conform::CaseResult& c : r.cases)
      if (c.technique == v.judged_as) right[c.scene] = c.status;
    for (const conform::CaseResult& c : r.cases) {
      if (c.technique != name) continue;
      const bool right_passes = !renderer::find_technique(v.judged_as) || right[c.scene] == conform::Status::Pass;
      if (c.status == conform::Status::Fail && right_passes) caught += " " + c.scene;
      if (c.status == conform::Status::Error) errors += " " + c.scene + " (" + c.error + ")";
    }
    EXPECT_TRUE(errors.empty()) << name << " could not be judged on:" << errors;
    EXPECT_FALSE(caught.empty()) << name << " (" << v.technique.description << ", judged as " << v.judged_as
                                 << ") is not a FAIL on any catalogue scene where the right technique passes; expected to be caught by " << v.caught_by;
    std::printf("%-34s caught (FAIL) on:%s\n", name.c_str(), caught.c_str());
  }
}

}  // namespace
}  // namespace shadowref
