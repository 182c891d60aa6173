// shadowref/record/status.hpp — the two tables of names a case of report.json carries: its status
// (the verdict under the catalogue's expectation) and its outcome against an engine team's
// expectations files. The one place each name is spelled: conform writes them, and every reader
// of report.json (the HTML, JUnit, summary.md, merge, diff) parses them back through here.
//
// Status of a case (VK-GL-CTS wording where it exists):
//   PASS   expected to pass, verdict pass
//   WARN   expected to pass, verdict quality warning (within the looser bound)
//   FAIL   expected to pass, verdict fail; or an expected failure whose errors are not the predicted ones
//   XFAIL  expected to fail (the catalogue's `why`), verdict fail: the limitation is detected and,
//          where the catalogue predicts the errors' kind or an engine's candidate is judged, its
//          errors are the predicted ones
//   XPASS  expected to fail, verdict pass or warning: a broken expectation, counted as a failure
//   ERROR  the case could not be judged (GL error, missing or unreadable candidate file)
// The rules that make a status (conform/status.hpp) and an outcome (conform/expectations.hpp) live
// with the run; these are only the names.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace shadowref::record {

enum class Status { Pass, Warn, Fail, XFail, XPass, Error };
inline constexpr std::array<Status, 6> kStatuses = {Status::Pass, Status::Warn, Status::Fail,
                                                    Status::XFail, Status::XPass, Status::Error};
const char* to_string(Status s);                                   // "PASS", "WARN", ...
std::optional<Status> status_from_string(std::string_view name);   // to_string's inverse; nullopt otherwise
bool is_failure(Status s);                                         // FAIL, XPASS, ERROR: a failure of the run

// What a case is against the expectations files (conform/expectations.hpp says when each holds).
enum class Outcome { Green, Expected, NewFailure, NewWarning, Improvement, Flake };
inline constexpr std::array<Outcome, 6> kOutcomes = {Outcome::Green,      Outcome::Expected,    Outcome::NewFailure,
                                                     Outcome::NewWarning, Outcome::Improvement, Outcome::Flake};
const char* to_string(Outcome o);  // "green", "expected", "new-failure", "new-warning", "improvement", "flake"
std::optional<Outcome> outcome_from_string(std::string_view name);  // to_string's inverse; nullopt otherwise
// Known (Expected) or flaky: not a failure of this run whatever the status says.
inline bool is_excused(Outcome o) { return o == Outcome::Expected || o == Outcome::Flake; }

}  // namespace shadowref::record
