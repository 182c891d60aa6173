// report_writer.hpp — report.json and the HTML report of a conformance run (private to the
// conform library): copies the images each case shows into <out>/report/img/ so the report
// folder stands alone (a CI artefact), then renders the page from report.json's data. The merge of
// shards (merge.cpp) publishes its report through the same functions.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowref/conform/conform.hpp"
#include "shadowref/outputs/staged_folder.hpp"

namespace shadowref::conform {

// The time now, UTC, as report.json's "generated" ("2026-11-27T20:15:00Z").
std::string now_utc();

void write_reports(const ConformResult& result, const ConformOptions& options, const std::filesystem::path& cache);

// report.json's "summary".
nlohmann::json summary_json(std::size_t cases, std::size_t pass, std::size_t warn, std::size_t fail, std::size_t xfail,
                            std::size_t xpass, std::size_t error, int exit_code);

// report.json's "expectations": the files, the count of each outcome over `cases` (report.json's
// cases, each with its "expectation"), the stale lines and the name of the next file.
nlohmann::json expectations_json(const ci::Expectations& e, const std::vector<const ci::ExpectationLine*>& stale,
                                 const nlohmann::json& cases);

// report.json's "triage", from which the page lets a person accept today's failures: "base", the
// expectations file without the new lines (expectations_update_text's, new_lines false: `e`'s lines
// still met, its [flakes] and [skips]), and "cases", each new failure and warning as
// {"scene", "technique", "line"} (known_line, the line the page adds when the case is marked).
nlohmann::json triage_json(const ci::Expectations& e, const std::vector<ci::CaseOutcome>& cases,
                           const std::vector<const ci::ExpectationLine*>& stale, const std::string& convention);

// Writes the page for `report` into `staged` (whose img/ is filled) and commits it, then
// report.junit.xml, summary.md, `update` as expectations-update.txt (when not empty) and report.json
// last, beside `report_json` (docs/output-contract.md: a report.json means the run finished).
void publish_reports(const nlohmann::json& report, outputs::StagedFolder& staged, const std::filesystem::path& report_json,
                     const std::string& update);

}  // namespace shadowref::conform
