// claims.md: the paper's claims C1–C6 (docs/reports.md §claims.md) with their verdicts, the exact definitions
// checked and the numbers behind each verdict.
#pragma once

#include <string>

#include "experiments/report/summary.hpp"

namespace rapid {

std::string claims_markdown(const Summary& summary);

}  // namespace rapid
