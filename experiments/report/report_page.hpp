// A sweep's report as one self-contained HTML page, report.html (docs/reports.md §report.html):
// provenance, Table I (sortable) with the probability of improvement and the IQMs, the claims
// with their verdicts and reasons, the figures inlined as PNG data URIs, and per cell every
// seed's curve, final return, status and links to its record and animation. Inline CSS and
// script, no network: it opens from file://. Made only from the files a summary leaves
// (report_folder.hpp), so a committed reports folder regenerates it byte for byte; nothing in it
// depends on the time, the machine or an absolute path.
//
// Opened with the fragment #selftest, the page's script checks itself (every sortable column
// sorts both ways, every figure decoded, every seed chart drawn, no script error) and writes the
// result as JSON into <pre id="selftest" data-status="pass|fail">, which tests/browser reads
// through headless Chromium.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "experiments/report/report_folder.hpp"

namespace rapid {

inline constexpr const char* kReportPage = "report.html";

std::string report_page_html(const ReportFolder& folder);

// Reads the folders (read_report_folder) and writes report_dir/report.html atomically. Returns
// the page's size in bytes. Throws std::invalid_argument for a folder it cannot make a page of.
std::uintmax_t write_report_page(const std::filesystem::path& report_dir, const std::filesystem::path& sweep_dir);

}  // namespace rapid
