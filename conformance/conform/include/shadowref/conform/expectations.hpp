// shadowref/conform/expectations.hpp — an engine team's known failures (an expectations file), the
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
// `scene@technique[@convention],STATUS` with STATUS one of WARN, FAIL, XPASS, ERROR (an unlisted
// case is expected to be green: PASS, XFAIL or a WARN the catalogue expects); without a convention
// it holds in every convention. `[flakes]` and `[skips]` hold ECMAScript regexes searched in the
// case's full name `scene@technique@convention` (std::regex_search, as deqp-runner's RegexSet); a
// `[baseline]` header goes back to case lines. Several files may be given: they are read as one,
// and a case listed twice is refused.
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
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "shadowref/conform/status.hpp"

namespace shadowref::conform {

// "scene@technique@convention": the name a case has in expectations files, regexes and JUnit.
std::string case_name(const std::string& scene, const std::string& technique, const std::string& convention);

struct ExpectationLine {
  std::string scene, technique, convention;  // convention empty: every convention
  Status status = Status::Fail;
  std::string where;                         // "file:line", for messages and the report
  std::string text;                          // the line as written, comment included
  bool applies_to(const std::string& scene, const std::string& technique, const std::string& convention) const;
};

struct ExpectationRegex {
  std::string pattern, where, text;
  std::regex regex;
};

struct Expectations {
  std::vector<std::filesystem::path> files;
  std::vector<ExpectationLine> lines;
  std::vector<ExpectationRegex> flakes, skips;
  bool empty() const { return files.empty(); }
  // The line for a case in `convention` (nullptr: none), and whether a [flakes] / [skips] regex
  // matches it.
  const ExpectationLine* line_for(const std::string& scene, const std::string& technique, const std::string& convention) const;
  bool flaky(const std::string& name) const;
  bool skipped(const std::string& name) const;
};

// Reads and checks the files. Throws std::invalid_argument with one line naming the file and the
// line: an unreadable file, a line without ",STATUS", an unknown or green status, a scene or
// technique that is not a safe identifier, an unknown convention, a bad regex, an unknown section,
// or the same case listed twice.
Expectations read_expectations(const std::vector<std::filesystem::path>& files);

enum class Outcome { Green, Expected, NewFailure, NewWarning, Improvement, Flake };
const char* to_string(Outcome o);  // "green", "expected", "new-failure", "new-warning", "improvement", "flake"

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
};

// Lines of `e` that match no case of a run in `convention` that planned `scenes` × `techniques`
// and skipped none of them (a scene of another shard is planned: its lines are not stale).
std::vector<const ExpectationLine*> stale_lines(const Expectations& e, const std::vector<std::string>& scenes,
                                                const std::vector<std::string>& techniques, const std::string& convention);

// The text of the expectations file that makes the next run of the same cases green: every line of
// `e` still met (as written, with its comment), a line for every new failure and warning
// (`scene@technique@convention,STATUS`), no line for an improvement or a stale line, lines for
// cases the run did not have (another convention) kept, and the [flakes] and [skips] sections.
std::string expectations_update_text(const Expectations& e, const std::vector<CaseOutcome>& cases,
                                     const std::vector<const ExpectationLine*>& stale, const std::string& convention);

}  // namespace shadowref::conform
