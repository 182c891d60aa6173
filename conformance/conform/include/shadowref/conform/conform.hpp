// shadowref/conform/conform.hpp — the conformance run: for each selected scene the reference
// (cached), for each technique a render (or an engine team's files), the comparison, the
// catalogue's expectation, and the case's status; then report.json and the HTML report.
//
// A case's status and the run's exit code follow status.hpp's rules; every verdict comes from the one
// judge (judge.hpp).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shadowref/compare/compare.hpp"
#include "shadowref/ci/expectations.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/ci/shard_plan.hpp"
#include "shadowref/conform/status.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/scene/scene.hpp"

#include "shadowref/renderer/faults.hpp"
#include "shadowref/renderer/gl_context.hpp"
#include "shadowref/renderer/renderer.hpp"

namespace shadowref::conform {

// A deliberately wrong variant of one of our techniques (the suite's teeth,
// conformance/tests/teeth_table.cpp): the renderer's technique `renders` with the fault switches
// `faults` on (renderer/faults.hpp), shown in the table and written under renders/ as `name`, and
// judged under the catalogue expectations and the threshold of the technique `judged_as`, or, when
// `judged_as` names no catalogue technique, as expected to pass with the strictest threshold.
struct ExtraTechnique {
  std::string name;
  std::string renders;
  renderer::Faults faults;
  std::string judged_as;
};

struct ConformOptions {
  std::vector<std::filesystem::path> scenes;    // scene files (catalogue.hpp selects them)
  std::vector<std::string> techniques;          // renderer technique names; empty: all
  const RunConvention* convention = &kDefaultConvention;  // the run convention (mathlib/convention.hpp)
  int shadow_map_size = 0;                      // texels per side of our shadow maps; 0: automatic
  // Our renders' correct variants (renderer::RenderOptions: random taps, depth faces, guard band,
  // normal offset); its faults are the teeth's to set, per extra technique.
  renderer::RenderOptions render_options;
  // Every scene rendered at another resolution (an engine's own): scale factor, or [W, H] (0: keep).
  double resolution_scale = 1.0;
  int width = 0, height = 0;
  renderer::Driver backend = renderer::Driver::Llvmpipe;
  renderer::GlApi gl_api = renderer::GlApi::OSMesa;
  std::filesystem::path out = "conformance-out";
  std::filesystem::path cache;                  // empty: <out>/reference-cache
  ReferenceSettings reference;
  int jobs = 0;                                 // threads for the reference; 0: the cores spare (outputs/spare_cores.hpp)
  // An engine team's renders instead of ours: <candidate_dir>/<scene>/mask.png (or
  // <scene>/<technique>/mask.png); `techniques` then names the one technique judged.
  std::optional<std::filesystem::path> candidate_dir;
  bool references_only = false;                 // fill the cache and stop (CTest fixtures)
  // How long one step may last before `stalled` hears of it, and again every time as long. Tests of
  // the run's stages shorten it to see which stage the run stands in (cmd: SHADOWREF_STALL_REPORT_MS).
  std::chrono::milliseconds stall_report_after = std::chrono::minutes(2);
  std::vector<ExtraTechnique> extra_techniques; // selectable by name in `techniques`
  bool write_report = true;                     // report.json and report/index.html
  // Each case's resolving power (resolving_power.hpp); off, report.json has none and every verdict,
  // metric and status is the same (a sweep that checks verdicts only).
  bool resolving_power = true;
  std::string command_line;                     // recorded in report.json
  // One shard of a split run (shard_plan.hpp): only the scenes the plan gives it, plus the control
  // case; none: the whole selection. `shard_weights` (scene -> seconds) balances the plan.
  std::optional<ci::ShardSpec> shard;
  std::map<std::string, double> shard_weights;
  std::filesystem::path shard_weights_file;     // recorded in report.json
  // An engine team's known failures (expectations.hpp); empty: the catalogue's expectations alone.
  ci::Expectations expectations;
};

struct CaseResult {
  std::string scene;
  std::filesystem::path scene_file;
  std::string technique;                        // as run (an extra technique's own name)
  // The catalogue's expectation for the technique judged, known before the case runs: an ERROR
  // case reports it too. When judged, it is the judgement's own `expectation`.
  scene::Expectation expected;
  Status status = Status::Error;
  // What the one judge found (judge.hpp); absent when the case ended in ERROR before a verdict.
  std::optional<CaseJudgement> judgement;
  std::string error;                            // ERROR: what went wrong
  std::filesystem::path reference_dir, candidate_dir;
  std::vector<std::string> error_images;        // in candidate_dir (ours) or out/errors/...
  std::vector<std::string> notes;               // the renderer's notes
  // Candidate files (masks, candidate.json, shaded.png) read through a symbolic link that leads out
  // of --candidate-dir: {file as read, where it really is}. Reading them is allowed; the report says so.
  std::vector<std::pair<std::string, std::string>> read_through_links;
  double frame_ms = 0;
  double seconds = 0;
  // Against the expectations files (expectations.hpp); `expected_line` names the line ("file:line")
  // and `expected_status` its status, when the case has one.
  Outcome outcome = Outcome::Green;
  std::string expected_status, expected_line;
  // Where the candidate says it was rendered (candidate.json's environment): what an expectations
  // line limited to an environment is matched with. Empty when none was declared or before a verdict.
  outputs::Environment environment;

  // The judgement's comparison, or null before a verdict.
  const compare::FolderComparison* comparison() const { return judgement ? &judgement->comparison : nullptr; }
};

// Where a run's time went, in seconds of wall time summed over the cases (bench/README.md reports
// these for the catalogue at 1024²): drawing (our renderer, llvmpipe), writing the candidate's
// files, judging (reading both folders, comparing, the cause model, the expected-failure signature)
// and writing the error images.
struct PhaseSeconds {
  double render = 0, write = 0, judge = 0, error_images = 0;
};

// What a run was asked to do, the same in every shard of it: the merge checks that shards agree.
struct RunPlan {
  std::vector<std::string> scenes;              // every selected scene, in table order (not only this shard's)
  std::map<std::string, int> shard_of;          // scene -> shard, 0-based (all 0 when not split)
  int shards = 1;
  std::string assignment = "hash";              // "hash" or "weights"
  std::string catalogue_id;                     // FNV-1a 64 of every planned scene's name and file bytes
  std::string control;                          // the control case's scene (split runs), or ""
};

struct ConformResult {
  std::vector<CaseResult> cases;
  std::vector<std::string> scenes, techniques;  // table order (this shard's scenes)
  RunPlan plan;
  std::optional<CaseResult> control;            // split runs: the control case every shard judges
  std::vector<std::string> skipped;             // cases a [skips] regex left out, by case_name()
  std::vector<const ci::ExpectationLine*> stale;  // expectation lines for no planned case (into options.expectations)
  std::string gl_vendor, gl_renderer, gl_version;
  std::string convention;
  double seconds = 0, reference_seconds = 0;
  PhaseSeconds phases;
  std::filesystem::path report_json, report_html;
  int exit_code() const;
  std::size_t count(Status s) const;
};

// One line per finished case, for the progress display: (done, total, case).
using Progress = std::function<void(std::size_t, std::size_t, const CaseResult&)>;
// One line for phases (references, the GL context).
using Log = std::function<void(const std::string&)>;

// Runs everything. Throws std::invalid_argument for bad options (unknown technique, backend),
// scene::SceneError for a broken scene file, renderer::GlError when no context can be created;
// a failure inside one case is that case's ERROR, not an exception. `stalled` hears, from a thread of
// its own, "still <step> after <n> s" every two minutes (options.stall_report_after) that one step
// (a reference, a case's drawing, judging or error images, the expectations, the reports) lasts: far
// beyond any step of the default run, so a hung run says where it stands.
ConformResult run_conform(const ConformOptions& options, const Progress& progress = {}, const Log& log = {},
                          const Log& stalled = {});

// The scene × technique table as text (one row per scene, one column per technique); with
// expectations files, each cell that is not green says what it is against them ("FAIL known",
// "FAIL new", "PASS improved", "FAIL flaky"), and a skipped case is "SKIP".
std::string table_text(const ConformResult& result, bool with_expectations = false);

// The cell's text for a case's status and outcome (table_text, and the merge's table).
std::string table_cell(Status status, Outcome outcome, bool with_expectations);

}  // namespace shadowref::conform
