#include "experiments/report/tables.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "algos/registry.hpp"
#include "core/contains.hpp"
#include "experiments/report/format.hpp"
#include "experiments/sweep/graph.hpp"

namespace rapid {

namespace {

std::vector<std::string> columns(const Summary& s) {
  return names_in_table_order(s.grid.algos);
}

int decimals_for(const Summary& s) {
  double magnitude = 0.0;
  for (const CellSummary& c : s.cells)
    if (c.mean) magnitude = std::max(magnitude, std::abs(*c.mean));
  return table_decimals(magnitude);
}

std::string count_note(const CellSummary& c) { return seed_count_note(c.n_ok, c.n_expected); }

std::string cell_text(const CellSummary* c, int decimals, const std::string& pm, const std::string& dash) {
  return c ? table_cell_text(c->mean, c->std, c->n_ok, c->n_expected, decimals, pm, dash) : "";
}

int total_expected(const Summary& s) {
  int n = 0;
  for (const CellSummary& c : s.cells) n += c.n_expected;
  return n;
}

std::string status_line(const Summary& s) {
  std::map<std::string, int> counts;
  for (const CellSummary& c : s.cells)
    for (const auto& [status, n] : c.statuses) counts[status] += n;
  std::string line;
  for (const auto& [status, n] : counts) line += (line.empty() ? "" : ", ") + std::to_string(n) + " " + status;
  return line;
}

// Every character LaTeX treats as a command: the input checks keep names plain (is_plain_text),
// and this keeps a table safe whatever reaches it.
std::string latex_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '\n': case '\r': out += ' '; break;
      case '_': case '&': case '%': case '#': case '$': case '{': case '}': out += '\\'; out += c; break;
      default: out += c;
    }
  }
  return out;
}

// "epsilon = 0.3, lambda_bc = 10": a row's axis values.
std::string point_text(const AxisPoint& point) {
  std::string out;
  for (const auto& [key, value] : point) out += (out.empty() ? "" : ", ") + key + " = " + axis_value_label(value);
  return out;
}

// The value of `key` in `point` ("" when the point has no such axis), CSV-quoted if needed.
std::string axis_text(const AxisPoint& point, const std::string& key) {
  for (const auto& [k, value] : point)
    if (k == key) {
      const std::string text = axis_value_label(value);
      return text.find(',') == std::string::npos ? text : "\"" + text + "\"";
    }
  return "";
}

// "`epsilon` over -0.5, -0.15 (all scenarios); …" for the table's preamble.
std::string axes_sentence(const Grid& grid) {
  std::string out;
  for (const GridAxis& axis : grid.axes) {
    out += (out.empty() ? "" : "; ") + std::string("`") + axis.key + "` over ";
    std::string per;
    for (const auto& [scenario, values] : axis.values) {
      std::string list;
      for (const auto& v : values) list += (list.empty() ? "" : ", ") + axis_value_label(v);
      per += (per.empty() ? "" : "; ") + list + " (" + scenario + ")";
    }
    out += per;
  }
  return out + ".";
}

// The sensitivity section: per axis, scenario and dataset, each algorithm's mean and 95% interval
// at every value of the axis.
std::string sensitivity_markdown(const Summary& s, int decimals) {
  std::ostringstream out;
  out << "\n## Sensitivity\n\nMean final return at each axis value, 95% stratified-bootstrap interval in brackets; "
         "the other axes held at the values named. An algorithm that does not read the axis shows the same cell "
         "at every value (marked *flat*).\n";
  std::string heading;
  for (const SensitivityLine& line : s.sensitivity) {
    const std::string h = "`" + line.axis + "` — " + scenario_display_name(line.scenario) + " / " +
                          dataset_display_name(line.dataset) + (line.others.empty() ? "" : " (" + point_text(line.others) + ")");
    if (h != heading) {
      heading = h;
      out << "\n### " << h << "\n\n| Algorithm |";
      for (const auto& v : line.values) out << " " << line.axis << " = " << axis_value_label(v) << " |";
      out << "\n|---|";
      for (std::size_t i = 0; i < line.values.size(); ++i) out << "---:|";
      out << "\n";
    }
    out << "| " << algo_display_name(line.algo) << (line.reads ? "" : " *flat*") << " |";
    for (std::size_t i = 0; i < line.values.size(); ++i) {
      if (!line.mean[i]) {
        out << " — |";
        continue;
      }
      out << " " << fixed(*line.mean[i], decimals);
      if (line.ci[i]) out << " [" << fixed(line.ci[i]->lo, decimals) << ", " << fixed(line.ci[i]->hi, decimals) << "]";
      out << " (n=" << line.n_ok[i] << ") |";
    }
    out << "\n";
  }
  return out.str();
}

// The last point of a curve as text ("—" for an empty curve).
std::string last_text(const MeanCurve& curve, int decimals) {
  return curve.empty() ? "—" : fixed(curve.mean.back(), decimals);
}

// What each cell's agents ended with: the collision rate of the last evaluation, the critic's
// mean Q and the imitation errors at the last logged update, and (records that log them) the
// gradients of the actor loss's two terms at the actor's output. They explain a return (CoL-all's
// imitation term is tiny beside Q; a low return with no collisions is a crawling agent).
std::string end_of_training_markdown(const Summary& s) {
  std::ostringstream out;
  const bool axes = !s.grid.axes.empty();
  const bool gradients =
      std::any_of(s.cells.begin(), s.cells.end(), [](const CellSummary& c) { return !c.q_grad_online.empty(); });
  out << "\n## End of training\n\nMeans over the ok seeds at the last logged point: the share of the last "
         "evaluation's episodes ended by a collision, the critic's mean Q over a batch, and the imitation error "
         "‖π(s) − a‖² on the batch's prior and online halves (logged for every algorithm, imitating or not).";
  if (gradients)
    out << " What moves the actor are the gradients at its output, per sample: the Q term's λ‖∂Q/∂a‖ and the "
           "imitation term's ‖2·w·(π(s) − a)‖ (w the algorithm's imitation weight: 0 where it does not imitate), "
           "on each half.";
  out << "\n\n| Scenario | Dataset | Algorithm |" << (axes ? " Axes |" : "")
      << " collisions | Q | BC error prior | BC error online |"
      << (gradients ? " Q grad prior | Q grad online | BC grad prior | BC grad online |" : "") << "\n|---|---|---|"
      << (axes ? "---|" : "") << "---:|---:|---:|---:|" << (gradients ? "---:|---:|---:|---:|" : "") << "\n";
  for (const CellSummary& c : s.cells) {
    if (c.n_ok == 0) continue;
    out << "| " << scenario_display_name(c.scenario) << " | " << (c.dataset.empty() ? "—" : dataset_display_name(c.dataset))
        << " | " << algo_display_name(c.algo) << " |" << (axes ? " " + point_text(c.axis) + " |" : "") << " "
        << last_text(c.collision_rate, 2) << " | " << last_text(c.q_value, 1) << " | " << last_text(c.bc_prior, 3)
        << " | " << last_text(c.bc_online, 3) << " |";
    if (gradients)
      out << " " << last_text(c.q_grad_prior, 3) << " | " << last_text(c.q_grad_online, 3) << " | "
          << last_text(c.bc_grad_prior, 3) << " | " << last_text(c.bc_grad_online, 3) << " |";
    out << "\n";
  }
  return out.str();
}

// A learned entropy temperature's course (records that log losses.temperature: RLPD (SAC)): the
// seeds' mean ± std at each quarter of training, and α(T) ÷ α(3T/4), so a reader sees whether it
// settles and where. Empty when no cell learns one.
std::string temperature_markdown(const Summary& s) {
  if (std::none_of(s.cells.begin(), s.cells.end(), [](const CellSummary& c) { return !c.temperature.empty(); }))
    return "";
  std::ostringstream out;
  out << "\n## The learned temperature\n\nThe entropy temperature α at the logged update nearest each quarter of "
         "training, mean ± std over the ok seeds, and the last quarter's change α(T) ÷ α(3T/4) of the means "
         "(1: settled; below 1: still falling).\n\n| Scenario | Dataset | Algorithm | T/4 | T/2 | 3T/4 | T | α(T) ÷ α(3T/4) |\n"
         "|---|---|---|---:|---:|---:|---:|---:|\n";
  for (const CellSummary& c : s.cells) {
    const MeanCurve& a = c.temperature;
    if (c.n_ok == 0 || a.empty()) continue;
    const auto at = [&](double fraction) {
      const double target = fraction * a.step.back();
      std::size_t best = 0;
      for (std::size_t i = 1; i < a.step.size(); ++i)
        if (std::abs(a.step[i] - target) < std::abs(a.step[best] - target)) best = i;
      return best;
    };
    out << "| " << scenario_display_name(c.scenario) << " | " << (c.dataset.empty() ? "—" : dataset_display_name(c.dataset))
        << " | " << algo_display_name(c.algo) << " |";
    for (const double q : {0.25, 0.5, 0.75, 1.0}) {
      const std::size_t i = at(q);
      out << " " << fixed(a.mean[i], 3) << " ± " << fixed(a.std[i], 3) << " |";
    }
    const double before = a.mean[at(0.75)];
    out << " " << (before > 0 ? fixed(a.mean.back() / before, 2) : "—") << " |\n";
  }
  return out.str();
}

// What the runs cost (s.run_costs): per scenario the median wall time of an algorithm's ok run with
// its range, then each algorithm's ok runs summed. Empty when no record says its time.
std::string run_cost_markdown(const Summary& s) {
  if (s.run_costs.empty()) return "";
  const std::vector<std::string> algos = columns(s);
  std::map<std::string, double> total_s;
  for (const RunCost& c : s.run_costs) total_s[c.algo] += c.total_s;
  std::ostringstream out;
  out << "\n## What a run cost\n\nWall time of one ok run in seconds, start to end (training and evaluation): "
         "the median over the scenario's cells and seeds, [fastest, slowest]. The time includes whatever else the "
         "machine ran (summary.json's provenance names the machines). Last, the table's ok runs summed, in hours of "
         "one process each (a local sweep gives each of its workers an equal share of the cores).\n\n| Scenario |";
  for (const std::string& a : algos) out << " " << algo_display_name(a) << " |";
  out << "\n|---|";
  for (std::size_t i = 0; i < algos.size(); ++i) out << "---:|";
  out << "\n";
  for (const std::string& scenario : s.grid.scenarios) {
    out << "| " << scenario_display_name(scenario) << " |";
    for (const std::string& a : algos) {
      const auto it = std::find_if(s.run_costs.begin(), s.run_costs.end(),
                                   [&](const RunCost& c) { return c.scenario == scenario && c.algo == a; });
      out << " " << (it == s.run_costs.end() ? "—" : run_cost_text(it->median_s, it->min_s, it->max_s)) << " |";
    }
    out << "\n";
  }
  out << "| All ok runs, hours |";
  for (const std::string& a : algos) out << " " << (total_s.count(a) ? short_number(total_s[a] / 3600.0) : "—") << " |";
  out << "\n";
  return out.str();
}

// What a run's final return is: its final evaluation (flow profile) or its last evaluations' mean.
std::string final_return_text(const Summary& s) {
  std::set<int> episodes;
  for (const CellSummary& c : s.cells)
    for (const SeedResult& r : c.seeds)
      if (r.final_return) episodes.insert(r.final_episodes);
  if (episodes.empty() || episodes.count(0)) return "mean of the last evaluations of each run";
  std::string n;
  for (int e : episodes) n += (n.empty() ? "" : " or ") + std::to_string(e);
  return "the mean over the " + n + " episodes of each run's final evaluation at the end of training";
}

}  // namespace

std::string table_markdown(const Summary& s) {
  const int decimals = decimals_for(s);
  std::ostringstream out;
  out << "# Table I — grid `" << s.grid.name << "`\n\n"
      << "Final return (" << final_return_text(s) << "), mean ± std over seeds; **bold** is the best mean of "
         "the row. `(n=k/N)`: only k of the N seeds finished ok (failed, diverged, missing or stale runs are not "
         "averaged in); `—`: no seed finished ok. DDPG uses no dataset: its value repeats in each row of its "
         "scenario.\n\n"
      << "Jobs: " << total_expected(s) << " runs, " << status_line(s) << ".\n\n";
  const auto algos = columns(s);
  const bool axes = !s.grid.axes.empty();
  if (axes)
    out << "Axes: " << axes_sentence(s.grid) << " A column shows its algorithm's cell at the values it reads; a cell "
        << "that does not read an axis repeats in the rows of all its values.\n\n";
  out << "| Scenario | Dataset |" << (axes ? " Axes |" : "");
  for (const auto& a : algos) out << " " << algo_display_name(a) << " |";
  out << "\n|---|---|" << (axes ? "---|" : "");
  for (std::size_t i = 0; i < algos.size(); ++i) out << "---:|";
  out << "\n";
  for (const TableRow& row : s.rows) {
    out << "| " << scenario_display_name(row.scenario) << " | " << dataset_display_name(row.dataset) << " |"
        << (axes ? " " + point_text(row.axis) + " |" : "");
    for (const auto& a : algos) {
      const std::string text = cell_text(s.column_cell(row, a), decimals, " ± ", "—");
      const bool best = row.best && *row.best == a;
      out << " " << (best ? "**" + text + "**" : text) << " |";
    }
    out << "\n";
  }

  if (!s.poi.empty()) {
    // Columns: (x, y) pairs, RAPID-RL against each baseline, then each variant of RAPID-RL against
    // RAPID-RL.
    std::vector<std::pair<std::string, std::string>> pairs;
    for (const auto& a : algos)
      if (is_baseline(a)) pairs.emplace_back(kRapidRl, a);
    for (const auto& a : algos)
      if (find_algorithm(a).variant) pairs.emplace_back(a, kRapidRl);
    const bool variants = !pairs.empty() && pairs.back().second == kRapidRl;
    out << "\n## Probability that RAPID-RL beats each baseline" << (variants ? " (and that each variant beats RAPID-RL)" : "")
        << "\n\nP(X > Y) over the ok seeds (Mann–Whitney U / (n_x·n_y), ties count half), 95% stratified-bootstrap "
           "interval in brackets.\n\n| Scenario | Dataset |" << (axes ? " Axes |" : "");
    for (const auto& [x, y] : pairs)
      out << (x == kRapidRl ? "" : " " + algo_display_name(x)) << " vs " << algo_display_name(y) << " |";
    out << "\n|---|---|" << (axes ? "---|" : "");
    for (std::size_t i = 0; i < pairs.size(); ++i) out << "---:|";
    out << "\n";
    for (const TableRow& row : s.rows) {
      out << "| " << scenario_display_name(row.scenario) << " | " << dataset_display_name(row.dataset) << " |"
          << (axes ? " " + point_text(row.axis) + " |" : "");
      const std::string point = point_label(row.axis);
      for (const auto& [x, y] : pairs) {
        const auto it = std::find_if(s.poi.begin(), s.poi.end(), [&](const PoiEntry& p) {
          return p.scenario == row.scenario && p.dataset == row.dataset && p.point == point && p.algo == x &&
                 p.baseline == y;
        });
        if (it == s.poi.end() || std::isnan(it->p)) out << " — |";
        else
          out << " " << fixed(it->p, 2) << (it->ci ? " [" + fixed(it->ci->lo, 2) + ", " + fixed(it->ci->hi, 2) + "]" : "") << " |";
      }
      out << "\n";
    }
  }
  if (!s.sensitivity.empty()) out << sensitivity_markdown(s, decimals);
  out << end_of_training_markdown(s);
  out << temperature_markdown(s);
  if (!s.aggregate.empty()) {
    out << "\n## IQM per algorithm over all cells\n\n"
        << "Interquartile mean of every ok run's final return, 95% stratified-bootstrap interval (strata = cells). "
           "Returns are not normalised across scenarios.\n\n| Algorithm | IQM | 95% CI | runs | cells |\n|---|---:|---:|---:|---:|\n";
    for (const AggregateEntry& a : s.aggregate)
      out << "| " << algo_display_name(a.algo) << " | " << fixed(a.iqm, decimals) << " | [" << fixed(a.ci.lo, decimals)
          << ", " << fixed(a.ci.hi, decimals) << "] | " << a.n_runs << " | " << a.n_cells << " |\n";
  }
  out << run_cost_markdown(s);
  return out.str();
}

std::string table_latex(const Summary& s) {
  const int decimals = decimals_for(s);
  const auto algos = columns(s);
  std::ostringstream out;
  out << "% Table I from the sweep grid '" << s.grid.name << "' (written by `rapid summarize`).\n"
      << "% Needs \\usepackage{booktabs} and \\usepackage[table]{xcolor} (for \\cellcolor).\n"
      << "\\begin{table}[t]\n\\centering\n"
      << "\\caption{The average final performance and one standard deviation over seeds of each algorithm across the "
         "driving scenarios and datasets. The cyan-shaded cell is the highest mean of each row; (n=k/N) marks cells "
         "where only k of N seeds finished.}\n"
      << "\\begin{tabular}{ll" << (s.grid.axes.empty() ? "" : "l") << std::string(algos.size(), 'c')
      << "}\n\\toprule\nScenario & Dataset" << (s.grid.axes.empty() ? "" : " & Axes");
  for (const auto& a : algos) out << " & " << latex_escape(algo_display_name(a));
  out << " \\\\\n";
  std::string previous;
  for (const TableRow& row : s.rows) {
    const bool first = row.scenario != previous;
    previous = row.scenario;
    if (first) out << "\\midrule\n" << latex_escape(scenario_display_name(row.scenario));
    out << " & " << latex_escape(dataset_display_name(row.dataset));
    if (!s.grid.axes.empty()) out << " & " << latex_escape(point_text(row.axis));
    for (const auto& a : algos) {
      const CellSummary* c = s.column_cell(row, a);
      std::string text;
      if (c && c->mean) {
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + temporary.
        text.append("$").append(fixed(*c->mean, decimals)).append(" \\pm ").append(fixed(*c->std, decimals)).append("$");
        if (c->n_ok < c->n_expected) text.append(" {\\scriptsize ").append(count_note(*c)).append("}");
      } else if (c) {
        text.append("--- {\\scriptsize ").append(count_note(*c)).append("}");
      }
      if (row.best && *row.best == a) text.insert(0, "\\cellcolor{cyan!15}");
      out << " & " << text;
    }
    out << " \\\\\n";
  }
  out << "\\bottomrule\n\\end{tabular}\n\\end{table}\n";
  return out.str();
}

std::string table_csv(const Summary& s) {
  const auto algos = columns(s);
  std::ostringstream out;
  out << "scenario,dataset";
  for (const GridAxis& axis : s.grid.axes) out << "," << axis.key;
  for (const auto& a : algos) out << "," << a << "_mean," << a << "_std," << a << "_n_ok," << a << "_n_expected";
  out << ",best\n";
  for (const TableRow& row : s.rows) {
    out << row.scenario << "," << row.dataset;
    for (const GridAxis& axis : s.grid.axes) out << "," << axis_text(row.axis, axis.key);
    for (const auto& a : algos) {
      const CellSummary* c = s.column_cell(row, a);
      if (!c) {
        out << ",,,,";
        continue;
      }
      out << "," << exact_number(c->mean) << "," << exact_number(c->std) << "," << c->n_ok << "," << c->n_expected;
    }
    out << "," << row.best.value_or("") << "\n";
  }
  return out.str();
}

namespace {

// The per-seed CSVs' identity of a cell, as their header names it: scenario, dataset (none for
// ddpg), algo and one column per grid axis.
std::string cell_csv_header(const Summary& s) {
  std::string header = "scenario,dataset,algo";
  for (const GridAxis& axis : s.grid.axes) header += "," + axis.key;
  return header;
}

std::string cell_csv_prefix(const Summary& s, const CellSummary& c) {
  std::string prefix = c.scenario + "," + (c.dataset.empty() ? sweep_files::kNoDataset : c.dataset) + "," + c.algo;
  for (const GridAxis& axis : s.grid.axes) prefix += "," + axis_text(c.axis, axis.key);
  return prefix;
}

}  // namespace

std::string finals_csv(const Summary& s) {
  std::ostringstream out;
  out << cell_csv_header(s) << ",seed,status,final_return,final_episodes\n";
  for (const CellSummary& c : s.cells) {
    const std::string prefix = cell_csv_prefix(s, c);
    for (const SeedResult& r : c.seeds)
      out << prefix << "," << r.seed << "," << r.status << "," << exact_number(r.final_return) << ","
          << (r.final_return ? std::to_string(r.final_episodes) : "") << "\n";
  }
  return out.str();
}

std::string runs_csv(const Summary& s) {
  std::ostringstream out;
  out << cell_csv_header(s) << ",seed,step,return\n";
  for (const CellSummary& c : s.cells) {
    const std::string prefix = cell_csv_prefix(s, c);
    for (const SeedResult& r : c.seeds)
      for (const auto& [step, ret] : r.eval)
        out << prefix << "," << r.seed << "," << exact_number(step) << "," << exact_number(ret) << "\n";
  }
  return out.str();
}

}  // namespace rapid
