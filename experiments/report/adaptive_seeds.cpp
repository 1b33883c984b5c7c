#include "experiments/report/adaptive_seeds.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <sstream>

#include "experiments/report/format.hpp"

namespace rapid {

namespace {
bool integer(const nlohmann::json& plan, const char* key) {
  return plan.contains(key) && plan[key].is_number_integer() && plan[key].get<long>() > 0;
}

std::string percent(double part, double whole) {
  std::ostringstream out;
  out << static_cast<long>(100.0 * part / whole + 0.5) << " %";
  return out.str();
}
}  // namespace

std::string seed_range(const nlohmann::json& seeds) {
  if (!seeds.is_array() || seeds.empty()) return "none";
  const std::string first = seeds.front().dump(), last = seeds.back().dump();
  return first == last ? first : first + "-" + last;
}

std::string look_verdicts_text(const nlohmann::json& look) {
  std::string text;
  const nlohmann::json verdicts = look.value("verdicts", nlohmann::json::object());
  for (const auto& [id, verdict] : verdicts.items())
    text += (text.empty() ? "" : ", ") + id + " " + (verdict.is_string() ? verdict.get<std::string>() : verdict.dump());
  return text;
}

std::string look_cells_text(const nlohmann::json& look) {
  std::string text;
  for (const nlohmann::json& c : look.value("cells", nlohmann::json::array()))
    text += (text.empty() ? "" : ", ") + (c.is_string() ? c.get<std::string>() : c.dump());
  return text;
}

std::string look_frozen_text(const nlohmann::json& look) {
  std::string text;
  const nlohmann::json frozen = look.value("frozen", nlohmann::json::array());
  for (const nlohmann::json& line : frozen)
    text += (text.empty() ? "" : "; ") + (line.is_string() ? line.get<std::string>() : line.dump());
  return text;
}

std::string rule_text(const nlohmann::json& a) {
  const nlohmann::json rule = a.value("rule", nlohmann::json());
  if (rule != "freeze")
    return "Each look decides every comparison afresh (the rule before issue #42, with which this folder's looks began).";
  return "A comparison is frozen at the look that decides it, at the look no undecided claim needs it any more, or "
         "at the look its conditional power at the maximum falls below " +
         fixed(a.value("futility", 0.0), 2) + " (futile); only the cells of comparisons still live get seeds.";
}

void check_decide_looks(const nlohmann::json& looks) {
  const auto bad = [](std::size_t i, const std::string& field, const std::string& expected) {
    throw std::invalid_argument("looks[" + std::to_string(i) + "]." + field + ": expected " + expected);
  };
  const auto strings = [](const nlohmann::json& v) {
    return v.is_array() && std::all_of(v.begin(), v.end(), [](const nlohmann::json& x) { return x.is_string(); });
  };
  for (std::size_t i = 0; i < looks.size(); ++i) {
    const nlohmann::json& look = looks[i];
    if (!look.is_object()) bad(i, "", "an object");
    if (!look.contains("look") || !look["look"].is_number_integer()) bad(i, "look", "a whole number");
    if (look.contains("verdicts") &&
        (!look["verdicts"].is_object() ||
         !std::all_of(look["verdicts"].begin(), look["verdicts"].end(), [](const nlohmann::json& v) { return v.is_string(); })))
      bad(i, "verdicts", "an object of claim: verdict");
    if (look.contains("added_seeds") &&
        (!look["added_seeds"].is_array() || look["added_seeds"].empty() ||
         !std::all_of(look["added_seeds"].begin(), look["added_seeds"].end(),
                      [](const nlohmann::json& v) { return v.is_number_unsigned(); })))
      bad(i, "added_seeds", "a list of seeds");
    if (look.contains("cells") && !strings(look["cells"])) bad(i, "cells", "a list of cell names");
    if (look.contains("frozen") && !strings(look["frozen"])) bad(i, "frozen", "a list of lines");
  }
}

nlohmann::json adaptive_seeds_summary(const nlohmann::json& plan, const std::vector<CellSummary>& cells,
                                      const RunProvenance& provenance) {
  if (!plan.is_object() || !plan.contains("initial_seeds") || !plan["initial_seeds"].is_array() ||
      !integer(plan, "block") || !integer(plan, "max_seeds") || !integer(plan, "looks_max") ||
      !plan.contains("looks") || !plan["looks"].is_array())
    return nullptr;
  check_decide_looks(plan["looks"]);
  const long initial = static_cast<long>(plan["initial_seeds"].size());
  const long max_seeds = plan["max_seeds"].get<long>();
  std::map<int, int> seeds_per_cell;  // ok seeds → cells with that many
  long runs = 0;
  for (const CellSummary& c : cells) {
    ++seeds_per_cell[c.n_ok];
    runs += c.n_ok;
  }
  nlohmann::json per_cell = nlohmann::json::object();
  for (const auto& [seeds, count] : seeds_per_cell) per_cell[std::to_string(seeds)] = count;
  const long n_cells = static_cast<long>(cells.size());
  return {{"initial_seeds", initial},
          {"rule", plan.value("rule", nlohmann::json("redecide"))},
          {"futility", plan.value("futility", nlohmann::json(nullptr))},
          {"block", plan["block"]},
          {"max_seeds", max_seeds},
          {"looks_max", plan["looks_max"]},
          {"looks", plan["looks"]},
          {"stopped", plan.contains("stopped") && plan["stopped"].is_string() ? plan["stopped"] : nlohmann::json(nullptr)},
          {"cells", n_cells},
          {"seeds_per_cell", per_cell},
          {"runs", runs},
          {"run_core_hours", provenance.run_wall_s / 3600.0},
          {"fixed_design_runs", {{"initial", n_cells * initial}, {"max", n_cells * max_seeds}}}};
}

std::string adaptive_seeds_markdown(const nlohmann::json& a) {
  if (!a.is_object()) return "";
  const long initial = a.value("initial_seeds", 0L), block = a.value("block", 0L);
  std::ostringstream out;
  out << "\n## Adaptive seeds (`rapid sweep --decide`)\n\n"
      << "The grid's " << initial << " seeds, then blocks of " << block
      << " seeds for the cells of undecided comparisons only, up to " << a.value("max_seeds", 0L)
      << " per cell, at most " << a.value("looks_max", 0L)
      << " looks, each deciding at α / looks (decide.json; docs/decisions.md). A look's verdicts are those of the "
         "seeds the cells had at it. "
      << rule_text(a) << "\n\n| look | verdicts | then |\n|---|---|---|\n";
  for (const nlohmann::json& look : a.value("looks", nlohmann::json::array())) {
    const std::size_t grown = look.value("cells", nlohmann::json::array()).size();
    std::string then = "the looks stop";
    if (look.contains("added_seeds"))
      then = "seeds " + seed_range(look["added_seeds"]) + " to " + std::to_string(grown) + " cell" +
             (grown == 1 ? "" : "s") + ": <details><summary>which</summary>" + look_cells_text(look) + "</details>";
    const std::size_t frozen = look.value("frozen", nlohmann::json::array()).size();
    if (frozen > 0)
      then += "; " + std::to_string(frozen) + " frozen: <details><summary>which</summary>" + look_frozen_text(look) +
              "</details>";
    out << "| " << look.value("look", 0) << " | " << look_verdicts_text(look) << " | " << then << " |\n";
  }
  const nlohmann::json stopped = a.value("stopped", nlohmann::json());
  out << "\n"
      << (stopped.is_string() ? "Stopped: " + stopped.get<std::string>() + "."
                              : std::string("The looks have not stopped: run the same `rapid sweep --decide` again."))
      << "\n\nSeeds per cell (ok runs; table.md's n):";
  std::string counts;
  const nlohmann::json per_cell = a.value("seeds_per_cell", nlohmann::json::object());
  for (const auto& [seeds, cells] : per_cell.items())
    counts += (counts.empty() ? " " : ", ") + cells.dump() + " cell" + (cells.get<long>() == 1 ? "" : "s") + " with " + seeds;
  const nlohmann::json fixed = a.value("fixed_design_runs", nlohmann::json::object());
  const double runs = a.value("runs", 0.0), fixed_max = fixed.value("max", 0.0);
  out << counts << ".\n\nCompute: " << a.value("runs", 0L) << " runs (" << short_number(a.value("run_core_hours", 0.0))
      << " core-hours of run time, summed over the ok records), against " << fixed.value("initial", 0L)
      << " runs for the fixed design at the grid's " << initial << " seeds and " << fixed.value("max", 0L)
      << " at the maximum for every cell";
  if (fixed_max > 0) out << " (" << percent(runs, fixed_max) << " of it)";
  out << ".\n";
  return out.str();
}

}  // namespace rapid
