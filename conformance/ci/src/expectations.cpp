// expectations.cpp — reading an engine team's expectations files, each case's outcome against them,
// and the next file to check in (expectations.hpp).
#include "shadowref/ci/expectations.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <re2/re2.h>

#include "shadowref/convention.hpp"
#include "shadowref/scene/identifier.hpp"

namespace shadowref::ci {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void refuse(const std::string& where, const std::string& what) { throw std::invalid_argument(where + ": " + what); }

// The statuses a line may name: the ones that are not green. An unlisted case is expected green.
Status line_status(const std::string& word, const std::string& where) {
  for (Status s : {Status::Warn, Status::Fail, Status::XPass, Status::Error})
    if (word == to_string(s)) return s;
  if (word == to_string(Status::Pass) || word == to_string(Status::XFail))
    refuse(where, "status " + word + " is what an unlisted case is expected to be: remove the line");
  refuse(where, "unknown status '" + word + "' (expected WARN, FAIL, XPASS or ERROR)");
}

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

// "api=webgpu adapter=swiftshader": the conditions of a line (expectations.hpp).
outputs::Environment parse_conditions(const std::string& text, const std::string& where) {
  outputs::Environment out;
  std::stringstream words(text);
  for (std::string w; words >> w;) {
    const auto eq = w.find('=');
    const std::string key = w.substr(0, eq);
    if (eq == std::string::npos || eq + 1 == w.size())
      refuse(where, "'" + w + "': expected a condition key=value (e.g. api=webgpu)");
    if (std::find(outputs::kEnvironmentKeys.begin(), outputs::kEnvironmentKeys.end(), key) == outputs::kEnvironmentKeys.end())
      refuse(where, "'" + w + "': unknown environment key '" + key + "' (expected api, adapter, browser or engine)");
    for (const auto& [k, v] : out)
      if (k == key) refuse(where, "'" + w + "': " + key + " is given twice");
    out.emplace_back(key, w.substr(eq + 1));
  }
  if (out.empty()) refuse(where, "an empty third field: give conditions key=value or remove the comma");
  return out;
}

// Whether two lines' conditions can both hold in one environment: unless some key has two values.
bool conditions_overlap(const outputs::Environment& a, const outputs::Environment& b) {
  for (const auto& [ka, va] : a)
    for (const auto& [kb, vb] : b)
      if (ka == kb && lower(va) != lower(vb)) return false;
  return true;
}

ExpectationLine parse_case_line(const std::string& body, const std::string& where) {
  const auto comma = body.find(',');
  if (comma == std::string::npos) refuse(where, "'" + body + "': expected scene@technique[@convention],STATUS");
  ExpectationLine l;
  l.where = where;
  const auto second = body.find(',', comma + 1);
  if (second != std::string::npos) {
    if (body.find(',', second + 1) != std::string::npos)
      refuse(where, "'" + body + "': expected scene@technique[@convention],STATUS[,key=value ...]: one comma too many");
    l.conditions = parse_conditions(body.substr(second + 1), where);
  }
  l.status = line_status(trim(body.substr(comma + 1, second == std::string::npos ? std::string::npos : second - comma - 1)), where);
  std::vector<std::string> parts;
  std::stringstream name(trim(body.substr(0, comma)));
  for (std::string p; std::getline(name, p, '@');) parts.push_back(trim(p));
  if (parts.size() < 2 || parts.size() > 3)
    refuse(where, "'" + body.substr(0, comma) + "': expected scene@technique[@convention]");
  l.scene = parts[0];
  l.technique = parts[1];
  for (const std::string* id : {&l.scene, &l.technique})
    if (const auto problem = scene::identifier_problem(*id)) refuse(where, "'" + *id + "': " + *problem);
  if (parts.size() == 3) {
    l.convention = parts[2];
    if (!find_run_convention(l.convention)) {
      std::string known;
      for (const RunConvention& c : kRunConventions) known += (known.empty() ? "" : ", ") + std::string(c.name);
      refuse(where, "unknown convention '" + l.convention + "' (expected one of " + known + ")");
    }
  }
  return l;
}

ExpectationRegex parse_regex(const std::string& body, const std::string& where) {
  ExpectationRegex r;
  r.pattern = body;
  r.where = where;
  RE2::Options options;
  options.set_log_errors(false);  // the refusal below is the one line said
  options.set_max_mem(kMaxRegexMemory);
  auto re = std::make_shared<const RE2>(body, options);
  if (!re->ok()) {
    // A pattern of thousands of characters is not repeated whole in the message.
    const std::string shown = body.size() > 80 ? body.substr(0, 77) + "..." : body;
    refuse(where, "bad regex '" + shown + "': " + re->error() + " (RE2 syntax)");
  }
  r.regex = std::move(re);
  return r;
}

void read_file(const std::filesystem::path& file, Expectations& e) {
  std::ifstream in(file);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(file, ec)) refuse(file.string(), "cannot read the expectations file");
  enum class Section { Baseline, Flakes, Skips } section = Section::Baseline;
  std::string raw;
  for (int n = 1; std::getline(in, raw); ++n) {
    // A UTF-8 byte-order mark (what editors on Windows put first) is not part of the first line.
    if (n == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);
    const std::string where = file.string() + ":" + std::to_string(n);
    const std::string body = trim(raw.substr(0, raw.find('#')));
    if (body.empty()) continue;
    if (body.front() == '[') {
      if (body == "[flakes]") section = Section::Flakes;
      else if (body == "[skips]") section = Section::Skips;
      else if (body == "[baseline]") section = Section::Baseline;
      else refuse(where, "unknown section '" + body + "' (expected [flakes], [skips] or [baseline])");
      continue;
    }
    if (section == Section::Baseline) {
      ExpectationLine l = parse_case_line(body, where);
      l.text = trim(raw);
      e.lines.push_back(std::move(l));
    } else {
      ExpectationRegex r = parse_regex(body, where);
      r.text = trim(raw);
      (section == Section::Flakes ? e.flakes : e.skips).push_back(std::move(r));
    }
  }
  if (in.bad()) refuse(file.string(), "cannot read the expectations file");
}

}  // namespace

std::string case_name(const std::string& scene, const std::string& technique, const std::string& convention) {
  return scene + "@" + technique + "@" + convention;
}

bool ExpectationLine::holds_in(const outputs::Environment& environment) const {
  for (const auto& condition : conditions) {
    const std::string& key = condition.first;  // a named reference: clang 14 captures no structured binding
    const auto it = std::find_if(environment.begin(), environment.end(), [&](const auto& e) { return e.first == key; });
    if (it == environment.end() || lower(it->second).find(lower(condition.second)) == std::string::npos) return false;
  }
  return true;
}

bool ExpectationLine::applies_to(const std::string& s, const std::string& t, const std::string& c,
                                 const outputs::Environment& environment) const {
  return s == scene && t == technique && (convention.empty() || convention == c) && holds_in(environment);
}

const ExpectationLine* Expectations::line_for(const std::string& s, const std::string& t, const std::string& c,
                                              const outputs::Environment& environment) const {
  for (const ExpectationLine& l : lines)
    if (l.applies_to(s, t, c, environment)) return &l;
  return nullptr;
}

bool ExpectationRegex::found_in(const std::string& name) const { return RE2::PartialMatch(name, *regex); }

bool Expectations::flaky(const std::string& name) const {
  return std::any_of(flakes.begin(), flakes.end(), [&](const ExpectationRegex& r) { return r.found_in(name); });
}

bool Expectations::skipped(const std::string& name) const {
  return std::any_of(skips.begin(), skips.end(), [&](const ExpectationRegex& r) { return r.found_in(name); });
}

Expectations read_expectations(const std::vector<std::filesystem::path>& files) {
  Expectations e;
  e.files = files;
  for (const auto& f : files) read_file(f, e);
  // The same case twice (in one file or two) would make the outcome depend on the order: refused.
  // A line for every convention and one for a single convention overlap in that convention.
  for (std::size_t i = 0; i < e.lines.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const ExpectationLine &a = e.lines[j], &b = e.lines[i];
      if (a.scene == b.scene && a.technique == b.technique &&
          (a.convention.empty() || b.convention.empty() || a.convention == b.convention) &&
          conditions_overlap(a.conditions, b.conditions))
        refuse(b.where, "case " + b.scene + "@" + b.technique + " is listed already at " + a.where);
    }
  return e;
}

Outcome outcome_of(Status s, bool expected_warning, const ExpectationLine* line, bool flaky) {
  // 0 green, 1 a warning of the run, 2 a failure: what "better" and "worse" compare.
  const auto rank = [&](Status st, bool catalogue_warn) { return is_failure(st) ? 2 : st == Status::Warn && !catalogue_warn ? 1 : 0; };
  const int seen = rank(s, expected_warning);
  if (flaky) return seen == 0 ? Outcome::Green : Outcome::Flake;
  if (!line) return seen == 2 ? Outcome::NewFailure : seen == 1 ? Outcome::NewWarning : Outcome::Green;
  if (s == line->status) return Outcome::Expected;
  const int expected = rank(line->status, false);
  if (seen < expected) return Outcome::Improvement;
  return seen == 2 ? Outcome::NewFailure : Outcome::NewWarning;
}

int exit_code(const std::vector<Outcome>& outcomes) {
  const auto any = [&](Outcome o) { return std::find(outcomes.begin(), outcomes.end(), o) != outcomes.end(); };
  if (any(Outcome::NewFailure)) return 2;
  if (any(Outcome::NewWarning) || any(Outcome::Improvement)) return 1;
  return 0;
}

std::vector<const ExpectationLine*> stale_lines(const Expectations& e, const std::vector<std::string>& scenes,
                                                const std::vector<std::string>& techniques, const std::string& convention,
                                                const std::vector<outputs::Environment>& environments) {
  std::vector<const ExpectationLine*> out;
  for (const ExpectationLine& l : e.lines) {
    if (!l.convention.empty() && l.convention != convention) continue;  // another convention's run has it
    if (!l.conditions.empty() &&
        std::none_of(environments.begin(), environments.end(), [&](const outputs::Environment& env) { return l.holds_in(env); }))
      continue;  // another environment's run has it
    const bool planned = std::find(scenes.begin(), scenes.end(), l.scene) != scenes.end() &&
                         std::find(techniques.begin(), techniques.end(), l.technique) != techniques.end();
    if (!planned && !e.skipped(case_name(l.scene, l.technique, convention))) out.push_back(&l);
  }
  return out;
}

std::string known_line(const CaseOutcome& c, const std::string& convention) {
  std::string limit;
  for (const auto& [k, v] : c.environment)
    if (k == "api" && v.find_first_of(" ,#") == std::string::npos) limit = ",api=" + v;
  return case_name(c.scene, c.technique, convention) + "," + to_string(c.status) + limit;
}

std::string expectations_update_text(const Expectations& e, const std::vector<CaseOutcome>& cases,
                                     const std::vector<const ExpectationLine*>& stale, const std::string& convention,
                                     bool new_lines) {
  std::ostringstream t;
  t << "# The expectations that make the next run of these cases green (shadowref, docs/ci.md): the lines\n"
       "# still met, one line per new failure or warning, no line for an improvement or a stale case.\n";
  std::set<const ExpectationLine*> gone(stale.begin(), stale.end());
  std::vector<std::string> added;
  for (const CaseOutcome& c : cases) {
    const ExpectationLine* l = e.line_for(c.scene, c.technique, convention, c.environment);
    if (c.outcome == Outcome::Improvement || c.outcome == Outcome::NewFailure || c.outcome == Outcome::NewWarning) {
      if (l) gone.insert(l);
      if (c.outcome != Outcome::Improvement && new_lines) added.push_back(known_line(c, convention) + "  # new in this run");
    }
  }
  for (const ExpectationLine& l : e.lines)
    if (!gone.count(&l)) t << l.text << "\n";
  for (const std::string& a : added) t << a << "\n";
  if (!e.flakes.empty()) {
    t << "[flakes]\n";
    for (const ExpectationRegex& r : e.flakes) t << r.text << "\n";
  }
  if (!e.skips.empty()) {
    t << "[skips]\n";
    for (const ExpectationRegex& r : e.skips) t << r.text << "\n";
  }
  return t.str();
}

}  // namespace shadowref::ci
