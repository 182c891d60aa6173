// shadowref/report/diff_html.hpp — the static page of `shadowref diff RUN_A RUN_B --out DIR`
// (DIR/diff.html), made from the diff's JSON alone, as the run's page is made from report.json.
//
// The page: both runs and the counts, the legend of the mask-difference picture, then one row per
// changed case: what changed, each run's status and wrong / unexplained pixels, and per light, side
// by side, A's candidate mask and error image, B's, and the picture of where the two masks differ.
// Plain HTML and CSS, no script and nothing fetched: it opens from file:// and as a CI artefact.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace shadowref::report {

// The page for `diff`: conform::to_json(RunDiff) with, added by the folder's writer, "legend"
// ([{name, colour: [r, g, b], legend}]) and per case "images" ([{mask, a_candidate, a_error,
// b_candidate, b_error, difference, differ}], paths relative to the page, "" for none). Missing
// fields are shown as "-".
std::string render_diff_html(const nlohmann::json& diff);

}  // namespace shadowref::report
