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
  if (report.is_discarded() || !report.is_object() || !report.contains("cases") || !report["cases"].is_array() ||
      !report.contains("plan") || !report["plan"].is_object())
    throw ReportUnreadable(file.string() + ": not a shadowref report.json with \"plan\" and \"cases\"");
  return report;
}

std::string report_text(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key)) return "(none)";
  return j[key].is_string() ? j[key].get<std::string>() : j[key].dump();
}

}  // namespace shadowref::conform
