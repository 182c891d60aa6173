// triage_html.hpp — the report page's triage (private to the report library): a person marks each
// new failure or warning of the run as known, with a bug link, and downloads the expectations file
// those marks make (docs/ci.md, "Triage in the report"). Made from report.json's "triage" alone
// (conform's report_writer: the file the run was given without its new lines, and each new case's
// line); the page stays static and offline, so the file is made in the browser.
#pragma once

#include <sstream>

#include "shadowref/record/run_record.hpp"

namespace shadowref::report {

// The section above the cases: how many are marked, the download button, the file as it stands,
// and the triage data for the script. Nothing when the report has no "triage" or no new case.
void triage_section(std::ostringstream& h, const record::TriageRecord& triage);

// Case `c`'s marks (a "known" box and a bug-link field) inside its row, when it is one of the
// report's new cases; nothing otherwise.
void triage_marks(std::ostringstream& h, const record::TriageRecord& triage, const record::CaseRecord& c);

// The page's script for both: builds the file from the marks, counts them, downloads it.
extern const char* const kTriageScript;

}  // namespace shadowref::report
