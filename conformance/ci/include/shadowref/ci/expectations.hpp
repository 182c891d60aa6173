// shadowref/ci/expectations.hpp — an engine team's known failures (an expectations file), the
// layer above the catalogue's own XFAILs: what each case of a run is against it, the exit code that
// follows, and the next file to check in (docs/ci.md).
//
// The file is deqp-runner's baseline shape (Mesa's `--baseline fails.txt`), one case per line:
//
//   # three.js BasicShadowMap: point-light near plane 0.5 (https://bugs.example/123)
//   light_near_caster@shadowmap,FAIL
//   sun_horizon@shadowmap@d3d,WARN          # only in the d3d convention
//   [flakes]
//   ^soft_.*@pcss@                          # regexes over "scene@technique@convention"
//   [skips]
//   ^large_sphere@
//
// `#` starts a comment (the bug link) anywhere on a line; blank lines are ignored. A case line is
// `scene@technique[@convention],STATUS[,CONDITIONS]` with STATUS one of WARN, FAIL, XPASS, ERROR (an
// unlisted case is expected to be green: PASS, XFAIL or a WARN the catalogue expects); without a
// convention it holds in every convention. CONDITIONS limit the line to an environment, as ANGLE's
// and wgpu's expectations do: space-separated `key=value` over the candidate's declared
// `environment` (outputs/candidate.hpp: api, adapter, browser, engine), each holding when that key's
// value contains `value`, case aside (`api=webgpu adapter=swiftshader`). A line limited so holds
// only for cases rendered there; for others the case is unlisted, and the line is neither stale nor
// an improvement in a run that has no case of its environment. Two lines of one case may differ by
// their conditions (a FAIL on WebGPU, a WARN on WebGL2) when some key is given different values. `[flakes]` and `[skips]` hold regexes searched in the case's full
// name `scene@technique@convention` (as deqp-runner's RegexSet), in RE2's syntax: a linear-time
// engine, so no pattern can take a run down (no backtracking blow-up, no recursion on nested
// groups); a pattern RE2 refuses (a syntax error, a back-reference or look-around, which RE2 does
// not have, a compiled program over kMaxRegexMemory) is refused with the line that holds it. A
// `[baseline]` header goes back to case lines. Several files may be given: they are read as one,
// and a case listed twice is refused. A UTF-8 byte-order mark at the start of a file is skipped
// (editors on Windows write one), as CR line ends are.
//
// What a case is against the expectations (Outcome), for its status S and its line's status E:
//   Green        S green (PASS, XFAIL, an expected WARN) and no line
//   Expected     S == E: a known failure, not a failure of this run
//   NewFailure   S a failure (FAIL, XPASS, ERROR) and no line, or a line with another status: exit 2
//   NewWarning   S an unexpected WARN and no line, or a line for no warning: exit 1
//   Improvement  S better than E (green where E is WARN or a failure; WARN where E is a failure):
//                exit 1 — nothing got worse, but the line must go, else the case could fail again
//                unseen under it (deqp-runner's UnexpectedImprovement, also not a success there)
//   Flake        S not green, the case matches a [flakes] regex: reported, never counted
// Without any file every case is Green, NewWarning or NewFailure, which is the catalogue's own exit
// code rule (status.hpp): one rule, with or without a file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/record/status.hpp"
#include "shadowref/outputs/candidate.hpp"

namespace re2 {
class RE2;
}

namespace shadowref::ci {

using record::Status;  // the statuses and their names are the record's (record/status.hpp)

// The memory RE2 may give one compiled [flakes] or [skips] pattern: a case-name pattern a person
// writes compiles to a few kilobytes; 1 MiB refuses only a pattern built to be huge.
inline constexpr long kMaxRegexMemory = 1L << 20;

// "scene@technique@convention": the name a case has in expectations files, regexes and JUnit.
std::string case_name(const std::string& scene, const std::string& technique, const std::string& convention);

struct ExpectationLine {
  std::string scene, technique, convention;  // convention empty: every convention
  Status status = Status::Fail;
  std::string where;                         // "file:line", for messages and the report
  std::string text;                          // the line as written, comment included
  outputs::Environment conditions;           // key=value conditions; empty: every environment
  bool applies_to(const std::string& scene, const std::string& technique, const std::string& convention,
                  const outputs::Environment& environment = {}) const;
  // Whether every condition holds in `environment` (a key it lacks fails its condition).
  bool holds_in(const outputs::Environment& environment) const;
};

struct ExpectationRegex {
  std::string pattern, where, text;
  std::shared_ptr<const re2::RE2> regex;  // compiled by read_expectations, never null there
  bool found_in(const std::string& name) const;  // RE2::PartialMatch: a search, as regex_search
};

struct Expectations {
  std::vector<std::filesystem::path> files;
  std::vector<ExpectationLine> lines;
  std::vector<ExpectationRegex> flakes, skips;
  bool empty() const { return files.empty(); }
  // The line for a case in `convention` (nullptr: none), and whether a [flakes] / [skips] regex
  // matches it.
  const ExpectationLine* line_for(const std::string& scene, const std::string& technique, const std::string& convention,
                                  const outputs::Environment& environment = {}) const;
  bool flaky(const std::string& name) const;
  bool skipped(const std::string& name) const;
};

// Reads and checks the files. Throws std::invalid_argument with one line naming the file and the
// line: an unreadable file, a line without ",STATUS", an unknown or green status, a scene or
// technique that is not a safe identifier, an unknown convention, a bad regex, an unknown section,
// or the same case listed twice.
Expectations read_expectations(const std::vector<std::filesystem::path>& files);

using record::Outcome;  // its names are the record's (record/status.hpp)

// The outcome of a case whose status is `s` (`expected_warning`: the catalogue expects its WARN)
// under `line` (nullptr: unlisted) and whether it matches a flake regex.
Outcome outcome_of(Status s, bool expected_warning, const ExpectationLine* line, bool flaky);

// The exit code of a run whose cases have these outcomes: 2 on a NewFailure, else 1 on a
// NewWarning or an Improvement, else 0.
int exit_code(const std::vector<Outcome>& outcomes);

// One case as the next expectations file needs it.
struct CaseOutcome {
  std::string scene, technique;
  Status status = Status::Pass;
  Outcome outcome = Outcome::Green;
  outputs::Environment environment;  // the candidate's declared environment (empty: none declared)
};

// Lines of `e` that match no case of a run in `convention` that planned `scenes` × `techniques`
// and skipped none of them (a scene of another shard is planned: its lines are not stale). A line
// limited to an environment that none of `environments` (those the run's cases declared) meets
// belongs to another run, as a line of another convention does: it is not stale.
std::vector<const ExpectationLine*> stale_lines(const Expectations& e, const std::vector<std::string>& scenes,
                                                const std::vector<std::string>& techniques, const std::string& convention,
                                                const std::vector<outputs::Environment>& environments = {});

// The line that makes case `c` known as it is now: `scene@technique@convention,STATUS`, limited to
// the case's `api=` when it declared one (seen on one API: expected there only, so the same case on
// another backend stays judged). What the next file says of a new failure or warning, and what the
// report page's triage writes for a case a person marks known.
std::string known_line(const CaseOutcome& c, const std::string& convention);

// The text of the expectations file that makes the next run of the same cases green: every line of
// `e` still met (as written, with its comment), a known_line for every new failure and warning
// (with `new_lines`; without, the file a person adds the lines they accept to), no line for an
// improvement or a stale line, lines for cases the run did not have (another convention) kept, and
// the [flakes] and [skips] sections.
std::string expectations_update_text(const Expectations& e, const std::vector<CaseOutcome>& cases,
                                     const std::vector<const ExpectationLine*>& stale, const std::string& convention,
                                     bool new_lines = true);

}  // namespace shadowref::ci
