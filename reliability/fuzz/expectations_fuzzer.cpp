// expectations_fuzzer.cpp — libFuzzer target: an expectations file as a CI hands it to `conform
// --expectations` (ci::read_expectations): case lines, environment conditions, [flakes] and
// [skips] regexes (RE2), comments, byte-order marks, any bytes. A file that is read is then used as
// a run uses it: each case's line and outcome, the flake and skip regexes searched in case names,
// the stale lines and the next file's text.
// Refusals must be std::invalid_argument with one line (what `conform` prints with exit 4);
// anything else escaping, a crash, a leak or a stall is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_files.hpp"
#include "shadowref/ci/expectations.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowref;
  static const std::filesystem::path file = fuzz::scratch_dir() / "fails.txt";
  fuzz::write_file(file, data, size);
  ci::Expectations e;
  try {
    e = ci::read_expectations({file});
  } catch (const std::invalid_argument& refused) {
    if (std::string(refused.what()).find('\n') != std::string::npos) __builtin_trap();  // one line, always
    return 0;
  }
  const outputs::Environment webgpu{{"api", "webgpu"}, {"adapter", "google swiftshader"}};
  for (const ci::ExpectationLine& l : e.lines) {
    for (const outputs::Environment& env : {outputs::Environment{}, webgpu}) {
      const ci::ExpectationLine* line = e.line_for(l.scene, l.technique, "gl", env);
      const std::string name = ci::case_name(l.scene, l.technique, "gl");
      (void)ci::outcome_of(ci::Status::Fail, false, line, e.flaky(name));
      (void)e.skipped(name);
    }
  }
  (void)e.flaky(std::string(64, 'a') + "@shadowmap@gl");
  const auto stale = ci::stale_lines(e, {"ground_sphere"}, {"shadowmap"}, "gl", {webgpu});
  (void)ci::expectations_update_text(
      e, {{"ground_sphere", "shadowmap", ci::Status::Fail, ci::Outcome::NewFailure, webgpu}}, stale, "gl");
  return 0;
}
