// judge_reads_test.cpp — one judgement reads each of its case's image files once: the staircase
// check, the comparison, the probes of the reference's own masks and (for a soft technique) the lit
// fraction all look at the images compare::read_folder_images read, never at the files again.
//
// Counted with outputs::image_files_read() around Judge::judge alone, probes on, for a shadow map
// (whose staircases are checked against the candidate's masks) and a soft technique (whose lit
// fraction adds the reference's covered pixels and the candidate's visibility.png). The reference's
// visibility exr is read by read_exr, once per soft light, and is not counted here.
#include <gtest/gtest.h>

#include <filesystem>

#include "catalogue_scene.hpp"
#include "llvmpipe_renderer.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;

// Our render of `technique` on `scene_name` judged once, probes on; returns the image files read.
std::size_t files_read_judging(const std::string& scene_name, const std::string& technique) {
  const test::CatalogueScene c(scene_name);
  const renderer::RenderResult r = test::llvmpipe_renderer().render(c.prepared, technique);
  const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / scene_name / technique;
  renderer::write_outputs(r, test::llvmpipe_renderer().info(), c.scene, dir);
  conform::Judge judge;  // with the resolving power: the probes read the reference's masks too
  const std::size_t before = outputs::image_files_read();
  const conform::CaseJudgement j = judge.judge(&c.prepared, {c.reference, dir, technique, true, {}});
  const std::size_t read = outputs::image_files_read() - before;
  EXPECT_EQ(j.comparison.decision.verdict, compare::Verdict::Pass) << scene_name << " x " << technique;
  EXPECT_TRUE(j.resolving_power) << "the probes ran";
  return read;
}

TEST(JudgeReads, AShadowMapCaseReadsTheReferenceMaskDecidedAndCandidateOnce) {
  EXPECT_EQ(files_read_judging("directional_light", "shadowmap"), 3u);  // mask.png, decided.png, candidate's mask.png
}

TEST(JudgeReads, ASoftCaseReadsItsLitFractionOnceBeside) {
  // The three masks, covered.png and the candidate's visibility.png.
  EXPECT_EQ(files_read_judging("soft_penumbra", "pcss"), 5u);
}

}  // namespace
}  // namespace shadowref
