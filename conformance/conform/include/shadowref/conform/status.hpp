// shadowref/conform/status.hpp — the status of a judged case under the catalogue's expectation, and
// the exit code of a run: the rules alone, with no I/O (status_test.cpp covers every one). The
// statuses and their names are the record's (record/status.hpp, which says what each means).
//
// Exit (docs/output-contract.md): 2 when any FAIL, XPASS or ERROR; else 1 when any WARN the catalogue
// does not expect ("result": "warn"); else 0.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shadowref/compare/compare.hpp"
#include "shadowref/record/status.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::conform {

using record::is_failure;
using record::Outcome;
using record::Status;
using record::status_from_string;
using record::to_string;

// The status of a verdict under an expectation (expected_pass false: an expected failure).
Status status_of(compare::Verdict verdict, bool expected_pass);

// An expectation the catalogue states that the verdict did not meet, said in the table's notes,
// report.json and the HTML (empty when met or when nothing was expected): a `warn` expectation
// met by a PASS. It changes no exit code: a PASS where a WARN was allowed is a better render than
// the catalogue's own (a larger map, a fitted cascade), never a defect; an expected failure that
// does not fail is an XPASS, a failure already.
std::string unmet_expectation(const scene::Expectation& expected, Status status);

// The exit code of a run whose cases have `statuses`, `expected_warnings[i]` saying whether case
// i's WARN is expected by the catalogue: 2 on any failure, 1 on an unexpected WARN, else 0.
int exit_code(const std::vector<Status>& statuses, const std::vector<bool>& expected_warnings);

// An expected failure that predicts the kind of its errors (scene::PredictedErrors): the errors of
// the other kind, judged on their own by the verdict's bounds (a 5x5 core, or a ratio to the same
// edge pixels or penumbra), must pass. Returns what they fail by, or "" when they pass; `seen`
// gets the predicted errors' counts for the signature.
std::string unpredicted_errors(const compare::FolderComparison& c, scene::PredictedErrors predicted, std::string& seen);

}  // namespace shadowref::conform
