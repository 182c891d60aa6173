// run_report.cpp — a finished run's report.json read back (run_report.hpp).
#include "shadowref/conform/run_report.hpp"

#include <algorithm>
#include <fstream>

namespace shadowref::conform {

namespace fs = std::filesystem;
using nlohmann::json;

json read_run_report(const fs::path& dir) {
  const fs::path file = dir / "report.json";
  std::ifstream in(file);
  if (!in) throw ReportUnreadable(file.string() + ": cannot read it (a run that did not finish has no report.json)");
  json report = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (report.is_discarded() || !report.is_object() || !report.contains(record::key::kCases) ||
      !report[record::key::kCases].is_array() || !report.contains(record::key::kPlan) || !report[record::key::kPlan].is_object())
    throw ReportUnreadable(file.string() + ": not a shadowref report.json with \"plan\" and \"cases\"");
  return report;
}

FinishedRun read_finished_run(const fs::path& dir) {
  FinishedRun r;
  r.report = read_run_report(dir);
  try {
    r.run = record::read_run(r.report);
  } catch (const record::RecordError& e) {
    throw ReportUnreadable((dir / "report.json").string() + ": " + e.what());
  }
  return r;
}

}  // namespace shadowref::conform
