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

// The case's outcome against an engine team's expectations files ("expected", "new-failure",
// "improvement", "flake", ...), or "" when the run had none.
std::string outcome(const json& c) {
  if (!c.contains("expectation") || !c["expectation"].is_object()) return "";
  return c["expectation"].value("outcome", "");
}

// "FAIL at fails.txt:3": what the expectations files said of the case ("green": no line).
std::string expected_by(const json& c) {
  const json& e = c["expectation"];
  return e.value("status", "green") + (e.contains("line") ? " at " + e.value("line", "") : "");
}

void write_file(const std::string& content, const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  outputs::write_file_atomically(file, content);
}

}  // namespace

BlindCases blind_cases(const json& report) {
  BlindCases b;
  std::map<std::string, std::size_t> kinds;
  for (const json& c : report.value("cases", json::array())) {
    if (!c.contains("resolving_power")) continue;
    ++b.judged;
    const json& blind = c["resolving_power"].value("blind_to", json::array());
    b.blind += !blind.empty();
    for (const json& k : blind) ++kinds[k.get<std::string>()];
  }
  for (const auto& [k, n] : kinds) b.kinds += (b.kinds.empty() ? "" : ", ") + k + ": " + std::to_string(n);
  return b;
}

std::string render_junit(const json& report) {
  const json cases = report.value("cases", json::array());
  std::size_t failures = 0, errors = 0, skipped = 0;
  for (const json& c : cases) {
    const std::string st = text(c, "status"), o = outcome(c);
    // A known failure or a flake is not a failure of this run: JUnit readers show it as skipped.
    if (o == "expected" || o == "flake") {
      skipped += st != "PASS" && st != "XFAIL";
      continue;
    }
    failures += st == "FAIL" || st == "XPASS";
    errors += st == "ERROR";
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"shadowref conform\" tests=\""
    << cases.size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped << "\">\n";
  for (const json& c : cases) {
    const std::string st = text(c, "status");
    x << "  <testcase classname=\"" << escape_html(text(c, "scene")) << "\" name=\"" << escape_html(text(c, "technique"))
      << "\" time=\"" << c.value("seconds", 0.0) << "\">";
    const std::string env = case_environment(c);
    if (c.contains("resolving_power") || !env.empty()) {
      x << "<properties>";
      if (c.contains("resolving_power"))
        x << "<property name=\"resolving_power\" value=\"" << escape_html(c["resolving_power"].value("summary", "")) << "\"/>";
      if (!env.empty()) x << "<property name=\"environment\" value=\"" << escape_html(env) << "\"/>";
      x << "</properties>";
    }
    const std::string o = outcome(c);
    if ((o == "expected" || o == "flake") && st != "PASS" && st != "XFAIL")
      x << "<skipped message=\"" << escape_html((o == "flake" ? "flaky: " + st : "known failure: " + expected_by(c)) + ": " + reasons(c)) << "\"/>";
    else if (o == "improvement")
      x << "<system-out>" << escape_html("improvement: " + st + " where the expectations say " + expected_by(c) + ": remove that line") << "</system-out>";
    else if (st == "FAIL" || st == "XPASS")
      x << "<failure message=\"" << escape_html((o == "new-failure" ? "new failure: " : "") + st + ": " + reasons(c)) << "\">" << escape_html(text(c, "why")) << "</failure>";
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
  m << " (convention " << cell(text(report, "convention")) << ")\n";
  // Where the candidates were rendered: one line per environment the cases declared.
  std::map<std::string, std::size_t> environments;
  for (const json& c : cases)
    if (const std::string env = case_environment(c); !env.empty()) ++environments[env];
  for (const auto& [env, n] : environments) m << "\nRendered on: " << cell(env) << " (" << n << " case(s))\n";
  if (report.contains("expectations")) {
    const json& e = report["expectations"];
    m << "\nAgainst the expectations files:";
    const json outcomes = e.value("counts", json::object());
    for (const auto& [k, v] : outcomes.items()) m << " " << v.dump() << " " << k << ",";
    m << " " << e.value("stale", json::array()).size() << " stale line(s); the next file: `expectations-update.txt`\n";
    for (const json& st : e.value("stale", json::array()))
      m << "- **stale** " << cell(st.value("line", "")) << ": `" << cell(st.value("text", "")) << "` names no case of this run\n";
  }
  if (report.contains("shard") && report["shard"].is_object())
    m << "\nShard " << report["shard"].value("index", 0) << "/" << report["shard"].value("total", 0) << " ("
      << cell(report["shard"].value("source", "")) << ")\n";
  m << "\n| scene |";
  for (const auto& t : techniques) m << " " << cell(t) << " |";
  m << "\n| --- |";
  for (std::size_t i = 0; i < techniques.size(); ++i) m << " --- |";
  m << "\n";
  for (const auto& s : scenes) {
    m << "| " << cell(s) << " |";
    for (const auto& t : techniques) {
      const auto it = at.find({s, t});
      const std::string st = it == at.end() ? "-" : it->second;
      const json* c = nullptr;
      for (const json& k : cases)
        if (text(k, "scene") == s && text(k, "technique") == t) c = &k;
      const std::string o = c ? outcome(*c) : "";
      const bool bad = (st == "FAIL" || st == "XPASS" || st == "ERROR") && o != "expected" && o != "flake";
      m << " " << (bad ? "**" + st + "**" : st) << (o.empty() || o == "green" ? "" : " (" + o + ")") << " |";
    }
    m << "\n";
  }
  const BlindCases blind = blind_cases(report);
  if (blind.judged)
    m << "\nResolving power: " << blind.blind << " of " << blind.judged
      << " judged cases are blind to a probe of the reference's own masks under their declaration"
      << (blind.blind ? " (" + cell(blind.kinds) + "): " + std::string(kHowToSharpen) : std::string(": none lets a probe that changes a decided pixel pass"))
      << "\n";
  bool any = false;
  for (const json& c : cases) {
    const std::string st = text(c, "status");
    if (st == "PASS" && outcome(c) != "improvement") continue;
    if (!any) m << "\n";
    any = true;
    const std::string o = outcome(c);
    m << "- **" << st << "**" << (o.empty() || o == "green" ? "" : " (" + o + (c["expectation"].contains("status") ? ": " + expected_by(c) : "") + ")")
      << " " << cell(text(c, "scene")) << " × " << cell(text(c, "technique"));
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
