// report_writer.hpp — report.json and the HTML report of a conformance run (private to the
// conform library): copies the images each case shows into <out>/report/img/ so the report
// folder stands alone (a CI artefact), then renders the page from report.json's data.
#pragma once

#include <filesystem>

#include "shadowref/conform/conform.hpp"

namespace shadowref::conform {

void write_reports(const ConformResult& result, const ConformOptions& options, const std::filesystem::path& cache);

}  // namespace shadowref::conform
