// shadowref/conform/run_report.hpp — reading back the report.json of a finished run (a `conform` or
// `merge` --out folder): what `merge` and `diff` both read, checked the same way.
//
// A folder is a finished run when its report.json parses as an object with "plan" (an object) and
// "cases" (an array): conform writes report.json last (docs/output-contract.md), so a run that was
// stopped has none. Image paths in a case are relative to the run's report/ folder and must stay in
// it: a report.json from elsewhere (a CI artefact) must not make a reader open files beside it.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "shadowref/record/case_record.hpp"
#include "shadowref/record/run_record.hpp"

namespace shadowref::conform {

// A report.json that is missing, does not parse or is not a run's: one line naming the file.
class ReportUnreadable : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The report.json in `dir`. Throws ReportUnreadable "<dir>/report.json: cannot read it (...)" or
// "<dir>/report.json: not a shadowref report.json with "plan" and "cases"".
nlohmann::json read_run_report(const std::filesystem::path& dir);

// A finished run as read back: its report.json as written (for the keys a merged report carries
// whole) and its record, through which every reader acts on it.
struct FinishedRun {
  nlohmann::json report;
  record::RunRecord run;
};

// read_run_report(dir) and its record. A record of the wrong shape throws ReportUnreadable
// "<dir>/report.json: <JSON path>: <what is wrong>" (record::read_run).
FinishedRun read_finished_run(const std::filesystem::path& dir);


// Whether `rel`, an image path of a case, is relative and has no ".." part (it stays in report/).
using record::inside_report_folder;

}  // namespace shadowref::conform
