// Reading a sweep folder into its Summary (summary.hpp): every cell's seeds from their records,
// the statistics over seeds, the curves, the table rows, the datasets' statistics and the claims.
#pragma once

#include <filesystem>

#include "experiments/report/summary.hpp"

namespace rapid {

struct SummaryOptions {
  bool dataset_stats = true;  // read the prior datasets (Figure 3(a)); `rapid diff` skips it
  bool claims = true;
  BootstrapSettings bootstrap;
};

// Reads the sweep folder's grid and every cell's record. Throws std::invalid_argument (one line)
// if DIR is not a sweep folder; a missing or broken record is a status, not an error.
Summary build_summary(const std::filesystem::path& sweep_dir, const SummaryOptions& options = {});

// Table I's rows of `s` from its grid and cells (what build_summary does after reading the cells),
// for a Summary made from elsewhere (a committed reports folder, report/decide_replay.hpp).
void build_table_rows(Summary& s);

}  // namespace rapid
