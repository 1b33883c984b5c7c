// Table I as Markdown, LaTeX (booktabs) and CSV (docs/reports.md). Rows are scenario × dataset, columns
// the grid's algorithms in the paper's order, a cell is "mean ± std" over the ok seeds of the
// final return. A cell short of seeds says so ("112.3 ± 4.1 (n=2/3)"); one with no ok seed shows
// "—" and its count. The best mean of each row is bold (Markdown) or shaded cyan (LaTeX).
#pragma once

#include <string>

#include "experiments/report/summary.hpp"

namespace rapid {

std::string table_markdown(const Summary& summary);
std::string table_latex(const Summary& summary);
// One line per row: scenario,dataset, then per algorithm mean,std,n_ok,n_expected (exact
// numbers, empty when there is no ok seed), then the best algorithm.
std::string table_csv(const Summary& summary);
// finals.csv: one line per run of every cell, `scenario,dataset,algo,<axes>,seed,status,
// final_return,final_episodes`: the number Table I averages (the final evaluation's mean, or with
// final_episodes 0 the mean of the last K evaluations); empty for a run that is not ok.
std::string finals_csv(const Summary& summary);

// runs.csv, the long format for pandas / seaborn / rliable: one line per ok run × evaluation,
// scenario,dataset,algo,<one column per axis>,seed,step,return (dataset "none" for ddpg; an axis
// column is empty for a cell that does not read it; step: the evaluation's target step).
std::string runs_csv(const Summary& summary);

}  // namespace rapid
