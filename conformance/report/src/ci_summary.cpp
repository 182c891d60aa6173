// ci_summary.cpp — JUnit XML and a Markdown summary from report.json (ci_summary.hpp).
#include "shadowref/report/ci_summary.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/report/html.hpp"

namespace shadowref::report {
namespace {

using nlohmann::json;

std::string text(const json& j, const char* key) {
  if (!j.contains(key)) return "";
  if (j[key].is_string()) return j[key].get<std::string>();
  return j[key].dump();
}

std::string reasons(const json& c) {
  std::string out;
  if (c.contains("comparison") && c["comparison"].contains("reasons"))
    for (const auto& r : c["comparison"]["reasons"]) out += (out.empty() ? "" : "; ") + r.get<std::string>();
  if (!text(c, "signature").empty()) out += (out.empty() ? "" : "; ") + text(c, "signature");
  if (!text(c, "error").empty()) out += (out.empty() ? "" : "; ") + text(c, "error");
  return out;
}

// Markdown table cells must not break the row.
std::string cell(std::string s) {
  for (char& ch : s)
    if (ch == '|' || ch == '\n') ch = ' ';
  return s;
}

void write_file(const std::string& content, const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  outputs::write_file_atomically(file, content);
}

}  // namespace

std::string render_junit(const json& report) {
  const json cases = report.value("cases", json::array());
  std::size_t failures = 0, errors = 0;
  for (const json& c : cases) {
    const std::string st = text(c, "status");
    failures += st == "FAIL" || st == "XPASS";
    errors += st == "ERROR";
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"shadowref conform\" tests=\""
    << cases.size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"0\">\n";
  for (const json& c : cases) {
    const std::string st = text(c, "status");
    x << "  <testcase classname=\"" << escape_html(text(c, "scene")) << "\" name=\"" << escape_html(text(c, "technique"))
      << "\" time=\"" << c.value("seconds", 0.0) << "\">";
    if (st == "FAIL" || st == "XPASS")
      x << "<failure message=\"" << escape_html(st + ": " + reasons(c)) << "\">" << escape_html(text(c, "why")) << "</failure>";
    else if (st == "ERROR")
      x << "<error message=\"" << escape_html(text(c, "error")) << "\"/>";
    else if (st == "XFAIL" || st == "WARN")
      x << "<system-out>" << escape_html(st + ": " + (st == "XFAIL" ? text(c, "why") : reasons(c))) << "</system-out>";
    x << "</testcase>\n";
  }
  x << "</testsuite>\n</testsuites>\n";
  return x.str();
}

std::string render_markdown(const json& report) {
  const json cases = report.value("cases", json::array());
  std::map<std::string, std::size_t> counts;
  std::vector<std::string> scenes, techniques;
  std::map<std::pair<std::string, std::string>, std::string> at;
  for (const json& c : cases) {
    const std::string s = text(c, "scene"), t = text(c, "technique");
    if (std::find(scenes.begin(), scenes.end(), s) == scenes.end()) scenes.push_back(s);
    if (std::find(techniques.begin(), techniques.end(), t) == techniques.end()) techniques.push_back(t);
    at[{s, t}] = text(c, "status");
    ++counts[text(c, "status")];
  }
  std::ostringstream m;
  m << "## shadowref conform\n\n" << cases.size() << " cases:";
  for (const char* st : {"PASS", "XFAIL", "WARN", "FAIL", "XPASS", "ERROR"}) m << " " << counts[st] << " " << st << ",";
  m.seekp(-1, std::ios_base::cur);
  m << " (convention " << cell(text(report, "convention")) << ")\n\n| scene |";
  for (const auto& t : techniques) m << " " << cell(t) << " |";
  m << "\n| --- |";
  for (std::size_t i = 0; i < techniques.size(); ++i) m << " --- |";
  m << "\n";
  for (const auto& s : scenes) {
    m << "| " << cell(s) << " |";
    for (const auto& t : techniques) {
      const auto it = at.find({s, t});
      const std::string st = it == at.end() ? "-" : it->second;
      m << " " << (st == "FAIL" || st == "XPASS" || st == "ERROR" ? "**" + st + "**" : st) << " |";
    }
    m << "\n";
  }
  bool any = false;
  for (const json& c : cases) {
    const std::string st = text(c, "status");
    if (st == "PASS") continue;
    if (!any) m << "\n";
    any = true;
    m << "- **" << st << "** " << cell(text(c, "scene")) << " × " << cell(text(c, "technique"));
    if (st == "XFAIL" || st == "XPASS") m << ": expected to fail: " << cell(text(c, "why"));
    const std::string r = reasons(c);
    if (!r.empty() && st != "XFAIL") m << (st == "XPASS" ? "; but only: " : ": ") << cell(r);
    m << "\n";
  }
  return m.str();
}

void write_junit(const json& report, const std::filesystem::path& file) { write_file(render_junit(report), file); }
void write_markdown(const json& report, const std::filesystem::path& file) { write_file(render_markdown(report), file); }

}  // namespace shadowref::report
