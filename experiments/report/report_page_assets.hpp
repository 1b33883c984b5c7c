// The style sheet and the script inlined into report.html (report_page.hpp), kept apart from the
// C++ that writes the content.
#pragma once

#include <string>

namespace rapid {

std::string report_page_css();
// Sorting of table.sortable by a header click, opening a drill-down its link points at, and the
// #selftest checks (report_page.hpp).
std::string report_page_script();

}  // namespace rapid
