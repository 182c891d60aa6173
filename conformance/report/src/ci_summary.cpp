// ci_summary.cpp — JUnit XML and a Markdown summary from report.json (ci_summary.hpp).
#include "shadowref/report/ci_summary.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/record/run_record.hpp"
#include "shadowref/report/html.hpp"

namespace shadowref::report {
namespace {

using nlohmann::json;

std::string reasons(const record::CaseRecord& c) {
  std::string out;
  for (const std::string& r : c.reasons) out += (out.empty() ? "" : "; ") + r;
  if (!c.signature.empty()) out += (out.empty() ? "" : "; ") + c.signature;
  if (!c.error.empty()) out += (out.empty() ? "" : "; ") + c.error;
  return out;
}

// Markdown table cells must not break the row.
std::string cell(std::string s) {
  for (char& ch : s)
    if (ch == '|' || ch == '\n') ch = ' ';
  return s;
}

// The case's outcome against an engine team's expectations files, nullopt when the run had none.
std::optional<record::Outcome> outcome(const record::CaseRecord& c) {
  return c.expectation ? std::optional<record::Outcome>(c.expectation->outcome) : std::nullopt;
}
bool is(const record::CaseRecord& c, record::Outcome o) { return outcome(c) == o; }
bool excused(const record::CaseRecord& c) { return c.expectation && record::is_excused(c.expectation->outcome); }
// Its name, "" when the run had no files.
std::string outcome_name(const record::CaseRecord& c) { return c.expectation ? to_string(c.expectation->outcome) : ""; }

// "FAIL at fails.txt:3": what the expectations files said of the case ("green": no line).
std::string expected_by(const record::CaseRecord& c) { return c.expectation ? c.expectation->expected_by() : "green"; }

void write_file(const std::string& content, const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  outputs::write_file_atomically(file, content);
}

}  // namespace

BlindCases blind_cases(const std::vector<record::CaseRecord>& cases) {
  BlindCases b;
  std::map<std::string, std::size_t> kinds;
  for (const record::CaseRecord& c : cases) {
    if (!c.resolving_power) continue;
    ++b.judged;
    b.blind += !c.resolving_power->blind_to.empty();
    for (const std::string& k : c.resolving_power->blind_to) ++kinds[k];
  }
  for (const auto& [k, n] : kinds) b.kinds += (b.kinds.empty() ? "" : ", ") + k + ": " + std::to_string(n);
  return b;
}

std::string render_junit(const json& report) {
  using record::Status;
  const std::vector<record::CaseRecord> cases = record::read_cases(report);
  std::size_t failures = 0, errors = 0, skipped = 0;
  for (const record::CaseRecord& c : cases) {
    // A known failure or a flake is not a failure of this run: JUnit readers show it as skipped.
    if (excused(c)) {
      skipped += c.status != Status::Pass && c.status != Status::XFail;
      continue;
    }
    failures += c.status == Status::Fail || c.status == Status::XPass;
    errors += c.status == Status::Error;
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"shadowref conform\" tests=\""
    << cases.size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped << "\">\n";
  for (const record::CaseRecord& c : cases) {
    const std::string st = to_string(c.status);
    x << "  <testcase classname=\"" << escape_html(c.scene) << "\" name=\"" << escape_html(c.technique)
      << "\" time=\"" << c.seconds << "\">";
    const std::string env = outputs::environment_text(c.environment);
    if (c.resolving_power || !env.empty()) {
      x << "<properties>";
      if (c.resolving_power)
        x << "<property name=\"resolving_power\" value=\"" << escape_html(c.resolving_power->summary) << "\"/>";
      if (!env.empty()) x << "<property name=\"environment\" value=\"" << escape_html(env) << "\"/>";
      x << "</properties>";
    }
    if (excused(c) && c.status != Status::Pass && c.status != Status::XFail)
      x << "<skipped message=\"" << escape_html((is(c, record::Outcome::Flake) ? "flaky: " + st : "known failure: " + expected_by(c)) + ": " + reasons(c)) << "\"/>";
    else if (is(c, record::Outcome::Improvement))
      x << "<system-out>" << escape_html("improvement: " + st + " where the expectations say " + expected_by(c) + ": remove that line") << "</system-out>";
    else if (c.status == Status::Fail || c.status == Status::XPass)
      x << "<failure message=\"" << escape_html((is(c, record::Outcome::NewFailure) ? "new failure: " : "") + st + ": " + reasons(c)) << "\">" << escape_html(c.why) << "</failure>";
    else if (c.status == Status::Error)
      x << "<error message=\"" << escape_html(c.error) << "\"/>";
    else if (c.status == Status::XFail || c.status == Status::Warn)
      x << "<system-out>" << escape_html(st + ": " + (c.status == Status::XFail ? c.why : reasons(c))) << "</system-out>";
    x << "</testcase>\n";
  }
  x << "</testsuite>\n</testsuites>\n";
  return x.str();
}

std::string render_markdown(const json& report) {
  using record::Status;
  const record::RunRecord run = record::read_run(report);
  const std::vector<record::CaseRecord>& cases = run.cases;
  std::map<Status, std::size_t> counts;
  std::vector<std::string> scenes, techniques;
  std::map<std::pair<std::string, std::string>, const record::CaseRecord*> at;
  for (const record::CaseRecord& c : cases) {
    if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
    if (std::find(techniques.begin(), techniques.end(), c.technique) == techniques.end()) techniques.push_back(c.technique);
    at[{c.scene, c.technique}] = &c;
    ++counts[c.status];
  }
  std::ostringstream m;
  m << "## shadowref conform\n\n" << cases.size() << " cases:";
  for (Status st : {Status::Pass, Status::XFail, Status::Warn, Status::Fail, Status::XPass, Status::Error})
    m << " " << counts[st] << " " << to_string(st) << ",";
  m.seekp(-1, std::ios_base::cur);
  m << " (convention " << cell(run.convention) << ")\n";
  // Where the candidates were rendered: one line per environment the cases declared.
  std::map<std::string, std::size_t> environments;
  for (const record::CaseRecord& c : cases)
    if (!c.environment.empty()) ++environments[outputs::environment_text(c.environment)];
  for (const auto& [env, n] : environments) m << "\nRendered on: " << cell(env) << " (" << n << " case(s))\n";
  if (run.expectations) {
    const record::ExpectationsRecord& e = *run.expectations;
    m << "\nAgainst the expectations files:";
    for (const auto& [outcome, n] : e.counts) m << " " << n << " " << outcome << ",";
    m << " " << e.stale.size() << " stale line(s); the next file: `" << cell(e.update) << "`\n";
    for (const record::StaleLineRecord& st : e.stale)
      m << "- **stale** " << cell(st.line) << ": `" << cell(st.text) << "` names no case of this run\n";
  }
  if (run.shard) m << "\nShard " << run.shard->index << "/" << run.shard->total << " (" << cell(run.shard->source) << ")\n";
  m << "\n| scene |";
  for (const auto& t : techniques) m << " " << cell(t) << " |";
  m << "\n| --- |";
  for (std::size_t i = 0; i < techniques.size(); ++i) m << " --- |";
  m << "\n";
  for (const auto& s : scenes) {
    m << "| " << cell(s) << " |";
    for (const auto& t : techniques) {
      const auto it = at.find({s, t});
      if (it == at.end()) {
        m << " - |";
        continue;
      }
      const record::CaseRecord& c = *it->second;
      const std::string st = to_string(c.status), o = outcome_name(c);
      const bool bad = is_failure(c.status) && !excused(c);
      m << " " << (bad ? "**" + st + "**" : st) << (o.empty() || is(c, record::Outcome::Green) ? "" : " (" + o + ")") << " |";
    }
    m << "\n";
  }
  const BlindCases blind = blind_cases(cases);
  if (blind.judged)
    m << "\nResolving power: " << blind.blind << " of " << blind.judged
      << " judged cases are blind to a probe of the reference's own masks under their declaration"
      << (blind.blind ? " (" + cell(blind.kinds) + "): " + std::string(kHowToSharpen) : std::string(": none lets a probe that changes a decided pixel pass"))
      << "\n";
  bool any = false;
  for (const record::CaseRecord& c : cases) {
    if (c.status == Status::Pass && !is(c, record::Outcome::Improvement)) continue;
    if (!any) m << "\n";
    any = true;
    const std::string st = to_string(c.status), o = outcome_name(c);
    m << "- **" << st << "**"
      << (o.empty() || is(c, record::Outcome::Green) ? "" : " (" + o + (!c.expectation->status.empty() ? ": " + expected_by(c) : "") + ")")
      << " " << cell(c.scene) << " × " << cell(c.technique);
    if (c.status == Status::XFail || c.status == Status::XPass) m << ": expected to fail: " << cell(c.why);
    const std::string r = reasons(c);
    if (!r.empty() && c.status != Status::XFail) m << (c.status == Status::XPass ? "; but only: " : ": ") << cell(r);
    m << "\n";
  }
  return m.str();
}

void write_junit(const json& report, const std::filesystem::path& file) { write_file(render_junit(report), file); }
void write_markdown(const json& report, const std::filesystem::path& file) { write_file(render_markdown(report), file); }

}  // namespace shadowref::report
