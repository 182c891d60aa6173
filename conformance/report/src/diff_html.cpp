// diff_html.cpp — the diff's JSON → diff.html (diff_html.hpp). Only the images are other files, and
// they are given relative to the page, so the folder opens anywhere.
#include "shadowref/report/diff_html.hpp"

#include <cctype>
#include <sstream>

#include "shadowref/report/html.hpp"

namespace shadowref::report {
namespace {

using nlohmann::json;

std::string text(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) return "-";
  return j[key].is_string() ? j[key].get<std::string>() : j[key].dump();
}

// The status badges share the run page's colours (html.cpp's st-* classes, repeated here because
// each page carries its own style sheet).
constexpr const char* kStyle = R"css(
body { margin:0; font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,sans-serif; color:#1d2330; background:#f6f7fa; }
header { background:#1d2330; color:#fff; padding:18px 28px; }
header h1 { margin:0 0 4px; font-size:22px; font-weight:600; }
header .meta { color:#c4cad6; font-size:13px; }
header code { color:#fff; }
main { padding:20px 28px 40px; }
section { background:#fff; border:1px solid #d9dee7; border-radius:8px; padding:16px 18px; margin-bottom:20px; }
h2 { font-size:17px; margin:0 0 12px; }
.legend span { display:inline-flex; align-items:center; margin-right:18px; font-size:13px; }
.legend i { display:inline-block; width:14px; height:14px; border-radius:3px; margin-right:6px; border:1px solid #0002; }
#cases { width:100%; border-collapse:collapse; }
#cases > tbody > tr { border-top:1px solid #d9dee7; }
#cases > tbody > tr > td { padding:14px 10px; vertical-align:top; }
.info { width:330px; }
.info h3 { margin:0 0 6px; font-size:15px; }
.info ul { margin:6px 0; padding-left:18px; font-size:13px; }
table.sides td, table.sides th { padding:1px 10px 1px 0; font-size:12.5px; text-align:left; }
.badge { display:inline-block; padding:1px 9px; border-radius:10px; font-weight:700; font-size:12px; }
.st-pass { background:#e6f4ea; color:#1e8e3e; } .st-fail { background:#fce8e6; color:#c5221f; }
.st-xfail { background:#fef3d6; color:#8a5a00; } .st-xpass { background:#fbe4f6; color:#a50e8e; }
.st-warn { background:#fff0db; color:#b06000; } .st-error { background:#5f6368; color:#fff; }
.light { margin-bottom:10px; white-space:nowrap; }
.light h4 { margin:0 0 4px; font-size:13px; font-weight:600; }
figure { margin:0 6px 0 0; display:inline-block; vertical-align:top; }
figure img { width:192px; height:auto; image-rendering:pixelated; border:1px solid #d9dee7; background:#888; display:block; }
figcaption, .notes { font-size:12px; color:#5b6475; margin-top:2px; }
)css";

std::string badge(const std::string& status) {
  std::string c = "st-";
  for (char ch : status) c += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return "<span class=\"badge " + escape_html(c) + "\">" + escape_html(status) + "</span>";
}

void figure(std::ostringstream& h, const std::string& src, const std::string& caption) {
  if (src.empty()) {
    h << "<figure><div class=\"notes\" style=\"width:192px\">(" << escape_html(caption) << ": none)</div></figure>";
    return;
  }
  h << "<figure><a href=\"" << escape_html(src) << "\"><img src=\"" << escape_html(src) << "\" alt=\"" << escape_html(caption)
    << "\"></a><figcaption>" << escape_html(caption) << "</figcaption></figure>";
}

// A case's left cell: what changed, and each run's status and counts.
void case_info(std::ostringstream& h, const json& c) {
  h << "<td class=\"info\"><h3>" << escape_html(text(c, "scene")) << " · " << escape_html(text(c, "technique")) << "</h3><ul>";
  for (const json& change : c.value("changes", json::array()))
    h << "<li>" << escape_html(change.is_string() ? change.get<std::string>() : change.dump()) << "</li>";
  h << "</ul><table class=\"sides\"><tr><th></th><th>A</th><th>B</th></tr>";
  const json a = c.value("a", json()), b = c.value("b", json());
  const auto cell = [](const json& side, const char* key) {
    return side.is_object() ? escape_html(text(side, key)) : std::string("-");
  };
  h << "<tr><td>status</td><td>" << (a.is_object() ? badge(text(a, "status")) : "not in A") << "</td><td>"
    << (b.is_object() ? badge(text(b, "status")) : "not in B") << "</td></tr>";
  h << "<tr><td>wrong px</td><td>" << cell(a, "wrong") << "</td><td>" << cell(b, "wrong") << "</td></tr>";
  h << "<tr><td>unexplained px</td><td>" << cell(a, "unexplained") << "</td><td>" << cell(b, "unexplained") << "</td></tr>";
  if (c.contains("mask_pixels_differ"))
    h << "<tr><td>masks differ</td><td colspan=\"2\">" << escape_html(text(c, "mask_pixels_differ")) << " of "
      << escape_html(text(c, "mask_pixels_compared")) << " px</td></tr>";
  h << "</table>";
  if (c.contains("masks_not_compared")) h << "<div class=\"notes\">" << escape_html(text(c, "masks_not_compared")) << "</div>";
  h << "</td>";
}

// A case's images, one line per light: A's candidate and error, B's, and where the masks differ.
void case_images(std::ostringstream& h, const json& c) {
  h << "<td>";
  for (const json& l : c.value("images", json::array())) {
    const auto src = [&](const char* key) {
      return l.is_object() && l.contains(key) && l[key].is_string() ? l[key].get<std::string>() : std::string();
    };
    h << "<div class=\"light\"><h4>" << escape_html(text(l, "mask")) << "</h4>";
    figure(h, src("a_candidate"), "A candidate");
    figure(h, src("a_error"), "A error");
    figure(h, src("b_candidate"), "B candidate");
    figure(h, src("b_error"), "B error");
    if (!src("difference").empty()) figure(h, src("difference"), "A vs B: " + text(l, "differ") + " px differ");
    h << "</div>";
  }
  h << "</td>";
}

}  // namespace

std::string render_diff_html(const json& d) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>shadowref diff: " << escape_html(text(d, "a"))
    << " against " << escape_html(text(d, "b")) << "</title><style>" << kStyle << "</style></head><body>\n";
  h << "<header><h1>shadowref diff</h1><div class=\"meta\">A <code>" << escape_html(text(d, "a")) << "</code> (convention "
    << escape_html(text(d, "convention_a")) << ")<br>B <code>" << escape_html(text(d, "b")) << "</code> (convention "
    << escape_html(text(d, "convention_b")) << ")<br>" << escape_html(text(d, "compared")) << " cases compared, "
    << escape_html(text(d, "changed")) << " changed (" << escape_html(text(d, "only_in_a")) << " only in A, "
    << escape_html(text(d, "only_in_b")) << " only in B)</div></header>\n<main>\n";
  h << "<section><h2>Reading the images</h2><div class=\"legend\"><span>candidate masks: white lit, black shadowed, grey no "
       "surface; error images as in each run's report.</span></div><div class=\"legend\" style=\"margin-top:8px\"><span>A vs B "
       "(B read against A):</span>";
  for (const json& l : d.value("legend", json::array())) {
    const json rgb = l.value("colour", json::array({0, 0, 0}));
    h << "<span><i style=\"background:rgb(" << rgb.at(0).dump() << "," << rgb.at(1).dump() << "," << rgb.at(2).dump() << ")\"></i>"
      << escape_html(text(l, "legend")) << "</span>";
  }
  h << "<span>dimmed: the masks agree (A's mask)</span></div></section>\n";
  h << "<section><h2>Changed cases</h2>";
  const json cases = d.value("cases", json::array());
  if (cases.empty()) h << "<p>Nothing changed.</p>";
  else {
    h << "<table id=\"cases\"><tbody>\n";
    for (const json& c : cases) {
      h << "<tr class=\"case\">";
      case_info(h, c);
      case_images(h, c);
      h << "</tr>\n";
    }
    h << "</tbody></table>";
  }
  h << "</section>\n</main></body></html>\n";
  return h.str();
}

}  // namespace shadowref::report
