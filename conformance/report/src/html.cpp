// html.cpp — report.json → report/index.html (html.hpp). Plain HTML and CSS, no external files
// but the images, so the folder opens anywhere (a CI artefact, a file:// URL).
#include "shadowref/report/html.hpp"

#include "shadowref/outputs/cause.hpp"

#include "shadowref/compare/compare.hpp"

#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/record/run_record.hpp"
#include "shadowref/report/ci_summary.hpp"
#include "triage_html.hpp"

namespace shadowref::report {
namespace {

using nlohmann::json;

// `v` in `format`; "-" when there is none.
std::string number_text(std::optional<double> v, const char* format = "%.4g") {
  if (!v) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, *v);
  return buf;
}

// A text of the run's record, "-" when the report did not say.
std::string shown(const std::optional<std::string>& s) { return s.value_or("-"); }
std::string shown(const std::string& s) { return s.empty() ? "-" : s; }

// A count of the record, "-" when the report did not say.
std::string count_text(std::optional<long long> n) { return n ? std::to_string(*n) : "-"; }

// "0", "0.0021", "2.8", "73", "100": two significant digits without exponents.
std::string short_percent(std::optional<double> percent) {
  if (!percent) return "-";
  const double v = *percent;
  char buf[32];
  std::snprintf(buf, sizeof buf, v >= 10 ? "%.0f" : "%.2g", v);
  return buf;
}

std::string anchor(const std::string& scene, const std::string& technique) {
  std::string a = "case-" + scene + "--" + technique;
  for (char& c : a)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return a;
}

// A case's outcome against the expectations files in words ("known failure", "new failure",
// "improvement", "flaky"), or "" when there were no files or the case is green.
std::string outcome_word(const record::CaseRecord& c) {
  if (!c.expectation) return "";
  switch (c.expectation->outcome) {
    case record::Outcome::Green: return "";
    case record::Outcome::Expected: return "known failure";
    case record::Outcome::NewFailure: return "new failure";
    case record::Outcome::NewWarning: return "new warning";
    case record::Outcome::Improvement: return "improvement";
    case record::Outcome::Flake: return "flaky";
  }
  return "";
}

std::string status_class(record::Status st) {
  std::string c = "st-";
  for (const char* ch = to_string(st); *ch; ++ch) c += static_cast<char>(std::tolower(static_cast<unsigned char>(*ch)));
  return c;
}

constexpr const char* kStyle = R"css(
:root { --fg:#1d2330; --muted:#5b6475; --line:#d9dee7; --bg:#f6f7fa; --card:#fff;
  --pass:#1e8e3e; --pass-bg:#e6f4ea; --fail:#c5221f; --fail-bg:#fce8e6; --xfail:#8a5a00; --xfail-bg:#fef3d6;
  --xpass:#a50e8e; --xpass-bg:#fbe4f6; --warn:#b06000; --warn-bg:#fff0db; --error:#fff; --error-bg:#5f6368; }
* { box-sizing: border-box; }
body { margin:0; font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif; color:var(--fg); background:var(--bg); }
header { background:#1d2330; color:#fff; padding:18px 28px; }
header h1 { margin:0 0 4px; font-size:22px; font-weight:600; }
header .meta { color:#c4cad6; font-size:13px; }
header .meta code { color:#fff; }
main { padding:20px 28px 40px; }
section { background:var(--card); border:1px solid var(--line); border-radius:8px; padding:16px 18px; margin-bottom:20px; }
h2 { font-size:17px; margin:0 0 12px; }
.counts span { display:inline-block; margin:0 8px 6px 0; padding:3px 10px; border-radius:12px; font-weight:600; font-size:13px; }
table { border-collapse:collapse; }
#summary th, #summary td { border:1px solid var(--line); padding:4px 8px; text-align:center; font-size:13px; }
#summary th { background:#eef1f6; font-weight:600; }
#summary td.scene { text-align:left; font-weight:600; white-space:nowrap; }
#summary td small { display:block; font-size:10.5px; opacity:.75; font-weight:400; }
#summary td a { display:block; text-decoration:none; color:inherit; font-weight:700; }
.st-pass { background:var(--pass-bg); color:var(--pass); }
.st-fail { background:var(--fail-bg); color:var(--fail); }
.st-xfail { background:var(--xfail-bg); color:var(--xfail); }
.st-xpass { background:var(--xpass-bg); color:var(--xpass); }
.st-warn { background:var(--warn-bg); color:var(--warn); }
.st-error { background:var(--error-bg); color:var(--error); }
.badge { display:inline-block; padding:1px 9px; border-radius:10px; font-weight:700; font-size:12px; letter-spacing:.03em; }
.legend span { display:inline-flex; align-items:center; margin-right:18px; font-size:13px; }
.legend i { display:inline-block; width:14px; height:14px; border-radius:3px; margin-right:6px; border:1px solid #0002; }
#cases { width:100%; }
#cases > tbody > tr { border-top:1px solid var(--line); }
#cases > tbody > tr > td { padding:14px 10px; vertical-align:top; }
#cases > thead th { text-align:left; font-size:12px; color:var(--muted); font-weight:600; padding:0 10px 6px; text-transform:uppercase; letter-spacing:.04em; }
#cases tr.case:target { outline:3px solid #4c8df6; outline-offset:-3px; }
.info { width:360px; }
.info h3 { margin:0 0 6px; font-size:15px; }
.info .why { margin:6px 0; padding:6px 9px; background:#f3f4f8; border-left:3px solid #a3abbd; font-size:13px; }
.info ul.reasons { margin:6px 0; padding-left:18px; font-size:13px; }
.info .error { color:var(--fail); font-weight:600; }
table.metrics td { padding:1px 10px 1px 0; font-size:12.5px; }
table.metrics td:first-child { color:var(--muted); }
figure { margin:0 0 8px; display:inline-block; }
figure img { width:192px; height:auto; image-rendering:pixelated; border:1px solid var(--line); background:#888; display:block; }
figure img.broken { outline:3px dashed var(--fail); min-height:40px; }
.viewer { display:inline-block; vertical-align:top; margin-left:8px; }
.viewer .stage { position:relative; width:256px; }
.viewer .stage img { width:256px; height:auto; image-rendering:pixelated; display:block; border:1px solid var(--line); }
.viewer .stage img.top { position:absolute; left:0; top:0; }
.viewer .stage img.overlay { position:absolute; left:0; top:0; opacity:0.45; mix-blend-mode:multiply; display:none; }
.viewer button.on { font-weight:bold; }
.viewer input[type=range] { width:256px; }
figcaption { font-size:12px; color:var(--muted); margin-top:2px; }
.notes { font-size:12px; color:var(--muted); }
.filters button { margin-right:6px; border:1px solid var(--line); background:#fff; border-radius:14px; padding:3px 12px; cursor:pointer; }
.filters button.on { background:#1d2330; color:#fff; }
#thresholds td, #thresholds th { border-bottom:1px solid var(--line); padding:4px 10px; text-align:left; font-size:13px; vertical-align:top; }
)css";

// Marks broken images and records counts on <body> (the Chromium test reads them from the DOM).
constexpr const char* kScript = R"js(
function shadowrefCheckImages() {
  var imgs = document.querySelectorAll('img'), broken = [];
  for (var i = 0; i < imgs.length; ++i) {
    var im = imgs[i];
    if (!im.complete || im.naturalWidth === 0) { im.classList.add('broken'); broken.push(im.getAttribute('src')); }
  }
  document.body.setAttribute('data-images', String(imgs.length));
  document.body.setAttribute('data-broken', String(broken.length));
  document.body.setAttribute('data-checked', '1');
  document.getElementById('broken-images').textContent = broken.join('\n');
}
window.addEventListener('load', shadowrefCheckImages);
// Image-diff modes of one case's viewer: swipe (slider = where the candidate starts), flicker
// (reference and candidate alternate every 0.5 s), amplify (the error image, slider = contrast).
function shadowrefView(button, mode) {
  var v = button.closest('.viewer'), base = v.querySelector('img.base'), top = v.querySelector('img.top');
  var slider = v.querySelector('input[type=range]'), note = v.querySelector('.notes');
  if (v.shadowrefTimer) { clearInterval(v.shadowrefTimer); v.shadowrefTimer = null; }
  var bs = v.querySelectorAll('button:not(:last-of-type)');
  for (var i = 0; i < bs.length; ++i) bs[i].classList.remove('on');
  button.classList.add('on');
  v.setAttribute('data-mode', mode);
  base.style.filter = ''; top.style.display = ''; slider.value = 50;
  if (mode === 'swipe') {
    base.src = v.getAttribute('data-ref'); top.style.clipPath = 'inset(0 0 0 50%)';
    note.textContent = 'swipe: reference left of the line, candidate right';
  } else if (mode === 'flicker') {
    base.src = v.getAttribute('data-ref'); top.style.clipPath = 'none';
    v.shadowrefTimer = setInterval(function () { top.style.display = top.style.display === 'none' ? '' : 'none'; }, 500);
    note.textContent = 'flicker: reference and candidate alternate';
  } else {
    base.src = v.getAttribute('data-err'); top.style.display = 'none';
    base.style.filter = 'contrast(4) brightness(1.2)';
    note.textContent = 'amplified error image (slider: contrast)';
  }
}
function shadowrefSlide(slider) {
  var v = slider.closest('.viewer'), mode = v.getAttribute('data-mode') || 'swipe';
  if (mode === 'swipe') v.querySelector('img.top').style.clipPath = 'inset(0 0 0 ' + slider.value + '%)';
  if (mode === 'amplify') v.querySelector('img.base').style.filter = 'contrast(' + (1 + slider.value / 10) + ') brightness(1.2)';
}
function shadowrefOverlay(button) {
  var o = button.closest('.viewer').querySelector('img.overlay');
  if (!o) return;
  o.style.display = o.style.display === 'block' ? 'none' : 'block';
  button.classList.toggle('on');
}
function shadowrefFilter(kind, button) {
  var rows = document.querySelectorAll('#cases tr.case');
  for (var i = 0; i < rows.length; ++i) {
    var s = rows[i].getAttribute('data-status');
    var show = kind === 'all' || (kind === 'problems' && (s === 'FAIL' || s === 'XPASS' || s === 'ERROR' || s === 'WARN')) ||
               (kind === 'xfail' && s === 'XFAIL');
    rows[i].style.display = show ? '' : 'none';
  }
  var bs = document.querySelectorAll('.filters button');
  for (var j = 0; j < bs.length; ++j) bs[j].classList.remove('on');
  button.classList.add('on');
}
)js";

void figure(std::ostringstream& h, const std::string& src, const std::string& caption) {
  if (src.empty()) {
    h << "<figure><div class=\"notes\">(" << escape_html(caption) << ": none)</div></figure>";
    return;
  }
  h << "<figure><a href=\"" << escape_html(src) << "\"><img src=\"" << escape_html(src) << "\" alt=\""
    << escape_html(caption) << "\" loading=\"eager\"></a><figcaption>" << escape_html(caption) << "</figcaption></figure>";
}

// The image-diff modes people use, on one light's images: side by side is the figures above; here
// flicker (reference and candidate toggled), swipe (the candidate revealed from the left by a slider),
// amplification (the error image's contrast raised) and the decided overlay (the reference's decided
// pixels darkened over what is shown).
void viewer(std::ostringstream& h, const record::LightRecord& l) {
  const std::string &ref = l.reference, &cand = l.candidate, &err = l.error, &dec = l.decided;
  if (ref.empty() || cand.empty()) return;
  h << "<div class=\"viewer\" data-ref=\"" << escape_html(ref) << "\" data-cand=\"" << escape_html(cand) << "\" data-err=\""
    << escape_html(err) << "\"><div>"
    << "<button onclick=\"shadowrefView(this,'swipe')\" class=\"on\">swipe</button> "
    << "<button onclick=\"shadowrefView(this,'flicker')\">flicker</button> "
    << "<button onclick=\"shadowrefView(this,'amplify')\">amplify error</button> "
    << "<button onclick=\"shadowrefOverlay(this)\">decided overlay</button></div>"
    << "<div class=\"stage\"><img class=\"base\" src=\"" << escape_html(ref) << "\" alt=\"reference\">"
    << "<img class=\"top\" src=\"" << escape_html(cand) << "\" alt=\"candidate\" style=\"clip-path:inset(0 0 0 50%)\">";
  if (!dec.empty()) h << "<img class=\"overlay\" src=\"" << escape_html(dec) << "\" alt=\"decided\">";
  h << "</div><input type=\"range\" min=\"0\" max=\"100\" value=\"50\" oninput=\"shadowrefSlide(this)\">"
    << "<div class=\"notes\">swipe: reference left of the line, candidate right</div></div>";
}

// One legend entry in the error images' own colour (outputs::kErrorClasses, the one definition).
std::string swatch(const outputs::Rgb& rgb, std::string_view label) {
  return "<span><i style=\"background:rgb(" + std::to_string(rgb[0]) + "," + std::to_string(rgb[1]) + "," +
         std::to_string(rgb[2]) + ")\"></i>" + std::string(label) + "</span>";
}

void metrics_table(std::ostringstream& h, const record::MaskMetricsRecord& m) {
  h << "<table class=\"metrics\">";
  const auto row = [&](const char* label, const std::string& v) {
    h << "<tr><td>" << label << "</td><td>" << escape_html(v) << "</td></tr>";
  };
  const auto n = count_text;
  row("wrong", n(m.wrong) + " (" + number_text(m.wrong_percent) + " %)");
  row("false shadow", n(m.false_shadow));
  row("false light", n(m.false_light));
  row("coverage", n(m.coverage));
  row("unexplained", n(m.unexplained) + " px (" + number_text(m.unexplained_percent_of_edges) + " % of " + n(m.edge_pixels) +
                         " edge px), core " + n(m.unexplained_core) + " px, of which " + n(m.acne) +
                         " self-shadowing (acne) and " + n(m.displaced) + " right once the shadows are moved back (displaced)");
  row("explained", n(m.texel) + " texel footprint + " + n(m.bias) + " depth bias (" + number_text(m.explained_percent_of_edges) +
                       " % of edge px)");
  row("largest region", n(m.largest_region) + " px (" + n(m.regions) + " regions)");
  row("decided surface px", n(m.decided_surface) + " of " + n(m.pixels));
  h << "</table>";
}

// Soft shadows: the lit fraction's numbers (comparison_json.hpp), in visibility units.
void visibility_table(std::ostringstream& h, const record::VisibilityRecord& v) {
  h << "<table class=\"metrics\"><tr><td colspan=\"2\"><b>lit fraction (visibility units)</b></td></tr>";
  const auto row = [&](const char* label, const std::string& value) {
    h << "<tr><td>" << label << "</td><td>" << escape_html(value) << "</td></tr>";
  };
  const bool random = v.sampling == "random";
  row("mean error over the penumbra", number_text(v.mean_penumbra_error, "%.3f") + (random ? " (noise bound " : " (bound ") +
                                          number_text(v.mean_penumbra_error_fail, "%.3f") + ")");
  if (random)
    row("mean error of the 3x3 local means", number_text(v.mean_penumbra_local_error, "%.3f") + " (bound " +
                                                 number_text(v.mean_penumbra_local_error_fail, "%.3f") + ": the width)");
  if (v.mean_penumbra_texel_error.value_or(0.0) > 0)
    row("the map's texel error", number_text(v.mean_penumbra_texel_error, "%.3f") +
                                     " over the penumbra, in both bounds in quadrature (a penumbra offset within half a texel)");
  row("unexplained", count_text(v.unexplained) + " px (" + number_text(v.unexplained_percent_of_penumbra) + " % of " +
                         count_text(v.penumbra) + " penumbra px; bound " + number_text(v.unexplained_fail_percent_of_penumbra) +
                         " %), core " + count_text(v.unexplained_core) + " px");
  row("explained", count_text(v.explained_footprint) + " px within the filter footprint's range");
  row("largest error", number_text(v.max_error, "%.3f"));
  row("judged px", count_text(v.judged) + " (covered by one surface)");
  h << "</table>";
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// The page's parts, in the order render_html writes them.
void expectations_section(std::ostringstream& h, const record::RunRecord& run);
void header_section(std::ostringstream& h, const record::RunRecord& run) {
  h << "<header><h1>shadowref conformance</h1><div class=\"meta\">";
  if (run.mode == "candidate-dir")
    h << "candidate renders from <code>" << escape_html(shown(run.candidate_dir)) << "</code>";
  else
    h << "backend <code>" << escape_html(shown(run.backend)) << "</code> via <code>" << escape_html(shown(run.gl_api))
      << "</code> · " << escape_html(shown(run.gl_renderer)) << " · OpenGL " << escape_html(shown(run.gl_version));
  h << " · reference: Embree, " << (run.samples_per_axis ? std::to_string(*run.samples_per_axis) : std::string("-"))
    << "² samples per pixel · " << escape_html(shown(run.tool)) << " " << escape_html(shown(run.version)) << " · "
    << escape_html(shown(run.generated)) << " · " << number_text(run.seconds, "%.1f") << " s</div></header>\n<main>\n";

}

// Counts and the scene × technique table.
void summary_section(std::ostringstream& h, const record::RunRecord& run) {
  const std::vector<record::CaseRecord>& records = run.cases;
  using record::Status;
  h << "<section><h2>Summary</h2><div class=\"counts\">";
  h << "<span style=\"background:#eef1f6\">cases " << records.size() << "</span>";
  for (const Status st : {Status::Pass, Status::XFail, Status::Fail, Status::XPass, Status::Warn, Status::Error}) {
    std::size_t n = 0;
    for (const record::CaseRecord& c : records) n += c.status == st;
    h << "<span class=\"" << status_class(st) << "\">" << to_string(st) << " " << n << "</span>";
  }
  h << "</div><p class=\"notes\">PASS: within the technique's threshold. XFAIL: a known limitation the catalogue "
       "expects, detected (its why is in the case). FAIL and XPASS (an expected failure that did not fail) are "
       "failures of the run; WARN is within the looser quality bound.</p>";
  if (const BlindCases b = blind_cases(records); b.judged)
    h << "<p class=\"notes\"><b>Resolving power:</b> " << b.blind << " of " << b.judged
      << " judged cases are blind to a probe of the reference's own masks under their declaration"
      << (b.blind ? " (" + escape_html(b.kinds) + "): " + escape_html(kHowToSharpen) : std::string(": none lets a probe that changes a decided pixel pass"))
      << ".</p>";
  const std::vector<std::string>&scenes = run.scenes, &techniques = run.techniques;
  std::map<std::pair<std::string, std::string>, std::size_t> at;  // the case's index in both
  for (std::size_t i = 0; i < records.size(); ++i) at[{records[i].scene, records[i].technique}] = i;
  h << "<table id=\"summary\"><thead><tr><th>scene</th>";
  for (const auto& t : techniques) h << "<th>" << escape_html(t) << "</th>";
  h << "</tr></thead><tbody>\n";
  for (const auto& s : scenes) {
    h << "<tr class=\"scene-row\"><td class=\"scene\">" << escape_html(s) << "</td>";
    for (const auto& t : techniques) {
      const auto it = at.find({s, t});
      if (it == at.end()) {
        h << "<td>-</td>";
        continue;
      }
      const record::CaseRecord& c = records[it->second];
      const std::string tip = c.total ? "wrong " + number_text(c.total->wrong_percent) + " %" : c.error;
      h << "<td class=\"" << status_class(c.status) << "\" title=\"" << escape_html(tip) << "\"><a href=\"#"
        << anchor(s, t) << "\">" << to_string(c.status) << "</a>"
        << (c.total ? "<small>" + short_percent(c.total->wrong_percent) + " %</small>" : std::string())
        << (outcome_word(c).empty() ? std::string() : "<small>" + escape_html(outcome_word(c)) + "</small>")
        << "</td>";
    }
    h << "</tr>\n";
  }
  h << "</tbody></table></section>\n";
  expectations_section(h, run);

}

// Against an engine team's expectations files: each outcome's count, the cases that are new or
// improved, and the stale lines (expectations.hpp's words).
void expectations_section(std::ostringstream& h, const record::RunRecord& run) {
  if (!run.expectations) return;
  const record::ExpectationsRecord& e = *run.expectations;
  h << "<section id=\"expectations\"><h2>Against the expectations files</h2><div class=\"counts\">";
  for (const auto& [outcome, n] : e.counts)
    h << "<span style=\"background:#eef1f6\">" << escape_html(outcome) << " " << n << "</span>";
  h << "<span style=\"background:#eef1f6\">stale " << e.stale.size() << "</span></div><ul>";
  for (const record::CaseRecord& c : run.cases) {
    if (!c.expectation) continue;
    const record::ExpectationRecord& x = *c.expectation;
    using record::Outcome;
    if (x.outcome != Outcome::NewFailure && x.outcome != Outcome::NewWarning && x.outcome != Outcome::Improvement) continue;
    h << "<li class=\"outcome\" data-outcome=\"" << to_string(x.outcome) << "\"><a href=\"#"
      << anchor(c.scene, c.technique) << "\">" << escape_html(c.scene + " · " + c.technique)
      << "</a>: " << escape_html(outcome_word(c)) << ", " << to_string(c.status) << " where the files expect "
      << escape_html(x.status.empty() ? "green" : x.status) << (x.line.empty() ? "" : " (" + escape_html(x.line) + ")")
      << (x.outcome == Outcome::Improvement ? ": remove the line" : "") << "</li>";
  }
  for (const record::StaleLineRecord& st : e.stale)
    h << "<li class=\"outcome\" data-outcome=\"stale\">stale " << escape_html(st.line) << ": <code>"
      << escape_html(st.text) << "</code> names no case of this run</li>";
  h << "</ul><p class=\"notes\">The next file, <code>" << escape_html(e.update) << "</code>, lies beside "
       "report.json.</p></section>\n";
}

// How to read the images: the mask values and the error colours (outputs/cause.hpp's one table).
void legend_section(std::ostringstream& h) {
  h << "<section><h2>Reading the images</h2><div class=\"legend\">"
    << "<span><i style=\"background:#fff\"></i>reference / candidate mask: white lit</span>"
    << "<span><i style=\"background:#000\"></i>black shadowed</span>"
    << "<span><i style=\"background:#808080\"></i>grey no surface</span></div><div class=\"legend\" style=\"margin-top:8px\">"
    << "<span>error image:</span>"
    ;
  for (const outputs::ErrorClassRow& r : outputs::kErrorClasses) h << swatch(r.colour, r.legend);
  const auto css = [](const outputs::Rgb& c) {
    return "rgb(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
  };
  h << "<span><i style=\"background:" << css(outputs::kDimmedLit) << "\"></i><i style=\"background:" << css(outputs::kDimmedShadowed)
    << "\"></i><i style=\"background:" << css(outputs::kDimmedNoSurface) << "\"></i>dimmed reference: lit, shadowed, no surface</span></div>"
    << "<div class=\"legend\" style=\"margin-top:8px\"><span>visibility error (soft shadows), brighter for larger |error|:</span>"
    << swatch(outputs::error_colour(outputs::ErrorClass::FalseShadow), "too dark, unexplained")
    << swatch(outputs::error_colour(outputs::ErrorClass::FalseLight), "too light, unexplained")
    << swatch(outputs::error_colour(outputs::ErrorClass::Texel), "within the filter footprint's range")
    << swatch(outputs::error_colour(outputs::ErrorClass::Undecided), "not judged: not covered by one surface")
    << "<span>grey: the reference's lit fraction, dimmed</span></div></section>\n";

}

// A declared number as report.json spells it (the shortest text that reads back as the same double).
std::string declared(double v) { return json(v).dump(); }

// The candidate's declaration as judged (its producer, map, filter, biases, per-light overrides and
// engine settings) and the environment it was rendered on.
void candidate_info(std::ostringstream& h, const record::CaseRecord& rec, const outputs::CandidateDeclaration& d) {
  // Volumes and planar shadows have no map, filter or bias: their settings would only list
  // defaults that mean nothing for them.
  const std::string& technique = rec.technique;
  const bool map_settings = !(technique.rfind("volume", 0) == 0 || technique == "planar");
  std::string defaulted;
  for (const std::string& key : d.defaulted)
    if (map_settings || key == "producer" || key == "version" || key == "convention")
      defaulted += (defaulted.empty() ? "" : ", ") + key;
  h << "<div class=\"notes\">candidate: " << escape_html(d.producer) << " " << escape_html(d.version) << " · "
    << escape_html(d.convention);
  if (map_settings)
    h << " · map "
      << (d.atlas_tile_size > 0 ? std::to_string(d.atlas_tile_size - 2 * d.atlas_guard_band) + " (an atlas tile of " +
                                      std::to_string(d.atlas_tile_size) + " with a guard band of " +
                                      std::to_string(d.atlas_guard_band) + ")"
                                : std::to_string(d.shadow_map_size))
      << " · filter " << declared(d.filter_radius_texels) << " texel · light taps " << d.light_taps << " ("
      << outputs::to_string(d.sampling) << ") · slope bias " << declared(d.slope_bias_texels) << " · constant bias "
      << declared(d.constant_bias) << " · normal offset " << declared(d.normal_offset) << " + "
      << declared(d.normal_offset_texels) << " texel · depth bias " << declared(d.depth_bias) << " · depth faces "
      << outputs::to_string(d.depth_faces)
      << (d.depth == outputs::StoredDepth::Distance ? " · distance maps over " + declared(d.depth_range) : std::string());
  h << (defaulted.empty() ? std::string() : " (defaulted: " + escape_html(defaulted) + ")") << "</div>";
  if (!rec.environment.empty())
    h << "<div class=\"notes environment\">rendered on: " << escape_html(outputs::environment_text(rec.environment)) << "</div>";
  // The per-light entries as the one writer spells them: only what differs from the top level.
  if (!d.lights.empty())
    h << "<div class=\"notes\">per light (overrides of the above, in the pack's light order): <code>"
      << escape_html(json::parse(outputs::declaration_text(d))["lights"].dump()) << "</code></div>";
  if (const json settings = json::parse(d.settings_json); !settings.empty())
    h << "<div class=\"notes\">engine settings (recorded, not judged): <code>" << escape_html(settings.dump()) << "</code></div>";
}

// A case's left cell: status, expectation, signature, declaration, reasons and numbers.
void case_info(std::ostringstream& h, const record::CaseRecord& rec) {
  const char* st = to_string(rec.status);
  h << "<tr class=\"case\" id=\"" << anchor(rec.scene, rec.technique) << "\" data-status=\""
    << st << "\"><td class=\"info\"><h3>" << escape_html(rec.scene) << " · "
    << escape_html(rec.technique) << "</h3><span class=\"badge " << status_class(rec.status) << "\">"
    << st << "</span> <span class=\"notes\">expected " << escape_html(rec.expected)
    << (rec.threshold.empty() ? std::string() : ", threshold " + escape_html(rec.threshold))
    << "</span>";
  if (!outcome_word(rec).empty())
    h << "<div class=\"why\"><b>expectations file:</b> " << escape_html(outcome_word(rec)) << " (expected "
      << escape_html(rec.expectation->status.empty() ? "green" : rec.expectation->status)
      << (rec.expectation->line.empty() ? std::string() : ", " + escape_html(rec.expectation->line)) << ")</div>";
  if (rec.shard || rec.host)
    h << "<div class=\"notes\">judged on " << escape_html(rec.host.value_or("?"))
      << (rec.shard ? ", shard " + std::to_string(*rec.shard) : std::string()) << "</div>";
  if (!rec.why.empty()) {
    const int from = rec.expected_from_height;
    h << "<div class=\"why\"><b>why it is expected to fail" << (from ? " from an image height of " + std::to_string(from) + " px" : "")
      << ":</b> " << escape_html(rec.why) << "</div>";
  }
  if (!rec.signature.empty()) h << "<div class=\"why\"><b>signature:</b> " << escape_html(rec.signature) << "</div>";
  if (!rec.unmet_expectation.empty())
    h << "<div class=\"why\"><b>expectation not met:</b> " << escape_html(rec.unmet_expectation) << "</div>";
  if (!rec.causes.empty()) h << "<div class=\"notes\">causes judged: " << escape_html(rec.causes) << "</div>";
  if (rec.resolving_power) {
    const bool blind = !rec.resolving_power->blind_to.empty();
    h << "<div class=\"" << (blind ? "why" : "notes") << "\"><b>resolving power:</b> " << escape_html(rec.resolving_power->summary)
      << (blind ? std::string(" (a probe of the reference's own masks that changes decided pixels and does not FAIL here: an error of that kind would "
                              "have passed too)")
                : std::string())
      << "</div>";
  }
  if (!rec.error.empty()) h << "<p class=\"error\">" << escape_html(rec.error) << "</p>";
  if (rec.candidate) candidate_info(h, rec, *rec.candidate);
  if (!rec.reasons.empty()) {
    h << "<ul class=\"reasons\">";
    for (const std::string& reason : rec.reasons) h << "<li>" << escape_html(reason) << "</li>";
    h << "</ul>";
  }
  if (rec.total) metrics_table(h, *rec.total);
  if (rec.visibility) visibility_table(h, *rec.visibility);
  if (!rec.notes.empty()) {
    h << "<div class=\"notes\">";
    for (const std::string& n : rec.notes) h << "note: " << escape_html(n) << "<br>";
    h << "</div>";
  }
  if (rec.frame_ms > 0) h << "<div class=\"notes\">frame " << number_text(rec.frame_ms, "%.1f") << " ms</div>";
}

// A case's right cell: per light, the reference, the candidate, the error image, the swipe viewer,
// and a soft technique's lit fraction, all from the case's record.
void case_images(std::ostringstream& h, const record::CaseRecord& rec) {
  if (rec.lights.empty()) {
    h << "<span class=\"notes\">no images: the case could not be compared</span>";
    return;
  }
  for (std::size_t i = 0; i < rec.lights.size(); ++i) {
    const record::LightRecord& l = rec.lights[i];
    const std::string suffix = rec.lights.size() > 1 ? " (light " + std::to_string(i) + ")" : "";
    h << "<div class=\"light\">";
    figure(h, l.reference, "reference" + suffix);
    figure(h, l.candidate, "candidate" + suffix);
    figure(h, l.error, "error" + suffix + ": " + count_text(l.metrics ? l.metrics->wrong : std::nullopt) + " wrong");
    viewer(h, l);
    if (i == 0) figure(h, rec.shaded, "candidate shaded");
    if (l.visibility) {
      figure(h, l.candidate_visibility, "candidate lit fraction" + suffix);
      figure(h, l.visibility_error,
             "visibility error" + suffix + ": mean " + number_text(l.visibility->mean_penumbra_error, "%.3f") +
                 " over the penumbra, " + count_text(l.visibility->unexplained) + " px unexplained");
    }
    h << "</div>";
  }
}

// Thresholds with their reasons.
void thresholds_section(std::ostringstream& h, const record::RunRecord& run) {
  h << "<section><h2>Thresholds</h2><table id=\"thresholds\"><thead><tr><th>name</th><th>bands</th><th>fail</th><th>warn</th><th>why</th></tr></thead><tbody>";
  for (const record::ThresholdRecord& t : run.thresholds)
    h << "<tr><td>" << escape_html(shown(t.name)) << "</td><td>" << (t.bands ? "texel, bias" : "none")
      << "</td><td>any unexplained core, or unexplained &gt; " << number_text(t.unexplained_fail_percent, "%.4g")
      << " % of edge px</td><td>explained &gt; " << number_text(t.explained_warn_percent, "%.4g") << " % of edge px</td><td>"
      << escape_html(shown(t.why)) << "</td></tr>";
  h << "</tbody></table><p class=\"notes\">Every wrong decided pixel is explained by a cause the reference computes "
       "(texel footprint, depth bias; shadow-map families only) or is unexplained. Edge pixels: the reference's "
       "boundaries, in pixels; the ratios mean the same at any resolution (docs/tolerance-model.md).</p></section>\n";
}

std::string render_html(const json& r) {
  std::ostringstream h;
  const record::RunRecord run = record::read_run(r);
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
    << "<title>shadowref conformance — " << escape_html(run.backend.value_or("candidate renders")) << "</title><style>"
    << kStyle << "</style></head>\n<body data-checked=\"0\">\n";

  header_section(h, run);
  summary_section(h, run);
  triage_section(h, run.triage);
  legend_section(h);
  // Cases, one row each.
  h << "<section><h2>Cases</h2><div class=\"filters\" style=\"margin-bottom:10px\">"
    << "<button class=\"on\" onclick=\"shadowrefFilter('all', this)\">all</button>"
    << "<button onclick=\"shadowrefFilter('problems', this)\">FAIL / XPASS / WARN / ERROR</button>"
    << "<button onclick=\"shadowrefFilter('xfail', this)\">XFAIL</button></div>"
    << "<table id=\"cases\"><thead><tr><th>case</th><th>reference · candidate · error · shaded</th></tr></thead><tbody>\n";
  for (std::size_t i = 0; i < run.cases.size(); ++i) {
    case_info(h, run.cases[i]);
    triage_marks(h, run.triage, run.cases[i]);
    h << "</td><td>";
    case_images(h, run.cases[i]);
    h << "</td></tr>\n";
  }
  h << "</tbody></table></section>\n";
  thresholds_section(h, run);
  h << "<pre id=\"broken-images\" class=\"notes\"></pre>\n</main>\n<script>" << kScript << kTriageScript << "</script>\n</body></html>\n";
  return h.str();
}

void write_html(const json& report, const std::filesystem::path& file) {
  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path());
  outputs::write_file_atomically(file, render_html(report));
}

}  // namespace shadowref::report
