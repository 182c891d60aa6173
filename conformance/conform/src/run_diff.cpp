// run_diff.cpp — two finished runs read back and compared case by case (run_diff.hpp).
//
// Every case is read through its record (record/case_record.hpp), which checks each field before use
// and names its JSON path when wrong: the report may come from another machine or another version (a
// CI artefact), and `diff` is how one looks at such reports, so it must say what is wrong rather
// than throw a type error.
#include "shadowref/conform/run_diff.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "shadowref/conform/mask_difference.hpp"
#include "shadowref/conform/run_report.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/record/case_record.hpp"

namespace shadowref::conform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A run's report.json with the file's name for messages.
struct RunReport {
  fs::path dir;
  std::string file;  // "<dir>/report.json"
  record::RunRecord run;

  [[noreturn]] void bad(const std::string& path, const std::string& what) const {
    throw ReportUnreadable(file + ": " + path + ": " + what);
  }
  // An image of the case's report/ copy (the record checked that it stays there): none for "".
  fs::path image(const std::string& rel) const { return rel.empty() ? fs::path() : dir / "report" / rel; }
};

std::vector<DiffLight> lights_of(const RunReport& r, const record::CaseRecord& rec) {
  std::vector<DiffLight> lights;
  for (const record::LightRecord& l : rec.lights) lights.push_back({l.mask, r.image(l.candidate), r.image(l.error)});
  return lights;
}

using CaseKey = std::pair<std::string, std::string>;  // scene, technique

// The cases of a run by scene@technique into `out`; returns their keys in the report's order. A case
// twice is refused.
std::vector<CaseKey> read_cases(const RunReport& r, std::map<CaseKey, DiffSide>& out) {
  std::vector<CaseKey> order;
  std::map<CaseKey, std::size_t> seen;
  for (std::size_t i = 0; i < r.run.cases.size(); ++i) {
    const record::CaseRecord& rec = r.run.cases[i];
    const std::string path = "cases[" + std::to_string(i) + "]";
    const CaseKey key{rec.scene, rec.technique};
    if (const auto it = seen.find(key); it != seen.end())
      r.bad(path, key.first + "@" + key.second + " is also cases[" + std::to_string(it->second) + "]");
    seen[key] = i;
    DiffSide s;
    s.status = to_string(rec.status);
    if (rec.total) {
      s.wrong = static_cast<std::size_t>(*rec.total->wrong);
      s.unexplained = static_cast<std::size_t>(*rec.total->unexplained);
    }
    s.lights = lights_of(r, rec);
    out[key] = std::move(s);
    order.push_back(key);
  }
  return order;
}

std::string mask_names(const DiffSide& s) {
  std::string out;
  for (const DiffLight& l : s.lights) out += (out.empty() ? "" : ", ") + l.mask;
  return out;
}

bool has_masks(const DiffSide& s) {
  return !s.lights.empty() && std::all_of(s.lights.begin(), s.lights.end(), [](const DiffLight& l) { return !l.candidate.empty(); });
}

// The two runs' candidate masks of a case, light by light.
MaskComparison compare_masks(const DiffSide& a, const DiffSide& b) {
  MaskComparison m;
  if (!has_masks(a) || !has_masks(b)) {
    m.not_compared = !has_masks(a) && !has_masks(b) ? "no candidate masks in either run"
                     : has_masks(a)                 ? "candidate masks in A only"
                                                    : "candidate masks in B only";
    m.not_compared_is_change = has_masks(a) || has_masks(b);
    return m;
  }
  if (mask_names(a) != mask_names(b)) {
    m.not_compared = "masks " + mask_names(a) + " in A, " + mask_names(b) + " in B";
    m.not_compared_is_change = true;
    return m;
  }
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    const outputs::Image8 ia = outputs::read_image8(a.lights[i].candidate, 1);
    const outputs::Image8 ib = outputs::read_image8(b.lights[i].candidate, 1);
    if (ia.width != ib.width || ia.height != ib.height) {
      m = MaskComparison{};
      m.not_compared = a.lights[i].mask + " is " + std::to_string(ia.width) + "x" + std::to_string(ia.height) + " in A, " +
                       std::to_string(ib.width) + "x" + std::to_string(ib.height) + " in B";
      m.not_compared_is_change = true;
      return m;
    }
    m.differ.push_back(count_differing_pixels(ia, ib));
    m.differ_total += m.differ.back();
    m.pixels_total += ia.pixel_count();
  }
  return m;
}

std::string count_text(const std::optional<std::size_t>& n) { return n ? std::to_string(*n) : "-"; }

// What changed in a case present in both runs, one phrase each.
std::vector<std::string> changes_of(const DiffSide& a, const DiffSide& b, const MaskComparison& m) {
  std::vector<std::string> out;
  if (a.status != b.status) out.push_back("status " + a.status + " -> " + b.status);
  if (a.wrong != b.wrong) out.push_back("wrong " + count_text(a.wrong) + " -> " + count_text(b.wrong));
  if (a.unexplained != b.unexplained) out.push_back("unexplained " + count_text(a.unexplained) + " -> " + count_text(b.unexplained));
  if (m.differ_total > 0)
    out.push_back("masks differ in " + std::to_string(m.differ_total) + " of " + std::to_string(m.pixels_total) + " px");
  if (m.not_compared_is_change) out.push_back(m.not_compared);
  return out;
}

RunReport read_run(const fs::path& dir) {
  RunReport r;
  r.dir = dir;
  r.file = (dir / "report.json").string();
  r.run = read_finished_run(dir).run;  // every case through its record: a status outside the table is refused
  return r;
}

json side_json(const std::optional<DiffSide>& s) {
  if (!s) return nullptr;
  json j = {{"status", s->status}, {"wrong", nullptr}, {"unexplained", nullptr}, {"masks", json::array()}};
  if (s->wrong) j["wrong"] = *s->wrong;
  if (s->unexplained) j["unexplained"] = *s->unexplained;
  for (const DiffLight& l : s->lights) j["masks"].push_back(l.mask);
  return j;
}

}  // namespace

std::size_t RunDiff::changed() const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [](const CaseDiff& c) { return c.changed(); }));
}
std::size_t RunDiff::only_in_a() const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [](const CaseDiff& c) { return !c.b; }));
}
std::size_t RunDiff::only_in_b() const {
  return static_cast<std::size_t>(std::count_if(cases.begin(), cases.end(), [](const CaseDiff& c) { return !c.a; }));
}

RunDiff diff_runs(const fs::path& a, const fs::path& b) {
  const RunReport ra = read_run(a), rb = read_run(b);
  std::map<CaseKey, DiffSide> sa, sb;
  std::vector<CaseKey> order = read_cases(ra, sa);
  for (const auto& key : read_cases(rb, sb))
    if (!sa.count(key)) order.push_back(key);
  RunDiff d;
  d.a = a;
  d.b = b;
  d.convention_a = ra.run.convention.empty() ? "(none)" : ra.run.convention;
  d.convention_b = rb.run.convention.empty() ? "(none)" : rb.run.convention;
  for (const auto& key : order) {
    CaseDiff c;
    c.scene = key.first;
    c.technique = key.second;
    if (const auto it = sa.find(key); it != sa.end()) c.a = it->second;
    if (const auto it = sb.find(key); it != sb.end()) c.b = it->second;
    if (c.a && c.b) {
      c.masks = compare_masks(*c.a, *c.b);
      c.changes = changes_of(*c.a, *c.b, c.masks);
    } else {
      c.changes.push_back(c.a ? "only in A" : "only in B");
    }
    d.cases.push_back(std::move(c));
  }
  return d;
}

json to_json(const RunDiff& d) {
  json j = {{"a", d.a.string()},
            {"b", d.b.string()},
            {"convention_a", d.convention_a},
            {"convention_b", d.convention_b},
            {"compared", d.cases.size()},
            {"changed", d.changed()},
            {"only_in_a", d.only_in_a()},
            {"only_in_b", d.only_in_b()},
            {"cases", json::array()}};
  for (const CaseDiff& c : d.cases) {
    if (!c.changed()) continue;
    json k = {{"scene", c.scene}, {"technique", c.technique}, {"changes", c.changes}, {"a", side_json(c.a)}, {"b", side_json(c.b)}};
    if (c.a && c.b) {
      k["mask_pixels_differ"] = c.masks.differ_total;
      k["mask_pixels_compared"] = c.masks.pixels_total;
      k["mask_pixels_differ_per_light"] = c.masks.differ;
      if (!c.masks.not_compared.empty()) k["masks_not_compared"] = c.masks.not_compared;
    }
    j["cases"].push_back(k);
  }
  return j;
}

std::string case_line(const CaseDiff& c) {
  const std::string label = !c.b ? "only A " : !c.a ? "only B " : "changed";
  std::string line = label + "  " + c.scene + "@" + c.technique + ": ";
  if (!c.a || !c.b) return line + (c.a ? c.a->status + " in A, not in B" : c.b->status + " in B, not in A");
  for (std::size_t i = 0; i < c.changes.size(); ++i) line += (i ? "; " : "") + c.changes[i];
  return line;
}

}  // namespace shadowref::conform
