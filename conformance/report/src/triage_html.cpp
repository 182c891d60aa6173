// triage_html.cpp — the report page's triage (triage_html.hpp): marks in the page, the
// expectations file made in the browser from report.json's "triage".
#include "triage_html.hpp"

#include <string>

#include "shadowref/report/html.hpp"

namespace shadowref::report {
namespace {

using nlohmann::json;

// A case's name as the marks and the data know it: "scene@technique".
std::string case_key(const std::string& scene, const std::string& technique) { return scene + "@" + technique; }

}  // namespace

void triage_section(std::ostringstream& h, const record::TriageRecord& triage) {
  if (triage.cases.empty()) return;
  json cases = json::array();
  for (const record::TriageLineRecord& c : triage.cases)
    cases.push_back({{record::key::kScene, c.scene}, {record::key::kTechnique, c.technique}, {record::key::kLine, c.line}});
  // The data rides in a JSON script element; every "<" (only ever inside a JSON string) is written
  // "\u003c", so no text of a file (a "</script>", a "<!--") can end or change the element.
  std::string data;
  for (const char ch : json{{record::key::kBase, triage.base}, {record::key::kCases, cases}}.dump()) data += ch == '<' ? "\\u003c" : std::string(1, ch);
  h << "<section id=\"triage\"><h2>Triage</h2><p class=\"notes\">Mark each new failure or warning you accept as known, "
       "with its bug link, in its row below; then download the expectations file the marks make: the file this run was "
       "given (its lines still met, its [flakes] and [skips]) and a line per mark. Checked in and passed to the next run "
       "with <code>--expectations</code>, the marked cases are known failures there; the unmarked stay new.</p>"
    << "<div class=\"counts\"><span id=\"triage-count\" style=\"background:#eef1f6\">0 of " << cases.size()
    << " marked</span> <button id=\"triage-download\" onclick=\"shadowrefTriageDownload()\">download expectations.txt</button>"
    << "</div><textarea id=\"triage-text\" readonly rows=\"8\" style=\"width:100%;margin-top:8px;font:12px monospace\">"
    << "</textarea><script type=\"application/json\" id=\"triage-data\">" << data << "</script></section>\n";
}

void triage_marks(std::ostringstream& h, const record::TriageRecord& triage, const record::CaseRecord& c) {
  for (const record::TriageLineRecord& t : triage.cases)
    if (t.scene == c.scene && t.technique == c.technique) {
      h << "<div class=\"triage\" data-case=\"" << escape_html(case_key(c.scene, c.technique)) << "\"><label><input type=\"checkbox\" "
           "class=\"triage-known\" onchange=\"shadowrefTriage()\"> known failure</label> <input type=\"url\" "
           "class=\"triage-bug\" placeholder=\"bug link\" size=\"28\" oninput=\"shadowrefTriage()\"></div>";
      return;
    }
}

// The file: the base's lines up to its first section header ([flakes], [skips], [baseline]), a line
// per marked case with its bug link as the comment, then the base's sections; a line for a case
// stays one line (newlines in a link are spaces). Recomputed at every change, shown in the text area.
const char* const kTriageScript = R"js(
function shadowrefTriage() {
  var el = document.getElementById('triage-data');
  if (!el) return '';
  var data = JSON.parse(el.textContent), lines = {}, marked = [];
  data.cases.forEach(function (c) { lines[c.scene + '@' + c.technique] = c.line; });
  document.querySelectorAll('.triage').forEach(function (t) {
    if (!t.querySelector('.triage-known').checked) return;
    var bug = t.querySelector('.triage-bug').value.replace(/[\r\n]+/g, ' ').trim();
    marked.push(lines[t.getAttribute('data-case')] + '  # ' + (bug || 'known failure') + ' (marked in the report)');
  });
  var base = data.base.split('\n');
  if (base.length && base[base.length - 1] === '') base.pop();
  var at = base.findIndex(function (l) { return /^\s*\[(flakes|skips|baseline)\]/.test(l); });
  if (at < 0) at = base.length;
  var text = base.slice(0, at).concat(marked, base.slice(at)).join('\n') + '\n';
  document.getElementById('triage-text').value = text;
  document.getElementById('triage-count').textContent = marked.length + ' of ' + data.cases.length + ' marked';
  return text;
}
function shadowrefTriageDownload() {
  var a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([shadowrefTriage()], {type: 'text/plain'}));
  a.download = 'expectations.txt';
  document.body.appendChild(a);
  a.click();
  a.remove();
}
window.addEventListener('load', shadowrefTriage);
)js";

}  // namespace shadowref::report
