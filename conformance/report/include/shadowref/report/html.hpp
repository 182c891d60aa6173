// shadowref/report/html.hpp — the static HTML report of a conformance run, made from the data of
// report.json alone (so that any report.json, ours or rebuilt, renders the same page).
//
// The page: a header (backend, GL strings, counts), the scene × technique table with a coloured
// cell per case linking to its row, the error-image legend, then the cases table, one row per
// case: status, expectation and its why, the verdict's reasons and metrics, and side by side the
// reference mask, the candidate mask, the error image and the candidate's shaded picture (per
// light). Image paths are relative to the page. A small script marks images that fail to load
// (img.complete && naturalWidth == 0) with class "broken" and records the count in
// <body data-images=N data-broken=M data-checked=1>, which the headless-Chromium test reads.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace shadowref::report {

// The page for `report` (the report.json object; missing fields are shown as "-").
std::string render_html(const nlohmann::json& report);

// Writes render_html(report) to `file` (creating its folder). Throws std::runtime_error.
void write_html(const nlohmann::json& report, const std::filesystem::path& file);

// "&", "<", ">", '"' and "'" escaped for HTML text and attribute values.
std::string escape_html(const std::string& text);

}  // namespace shadowref::report
