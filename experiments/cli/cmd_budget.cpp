// `rapid budget DIR`: the flow profile's budget rule (docs/datasets.md) applied to the reference
// DDPG runs under DIR, per scenario: the plateau check and the table's budget T.
#include <iostream>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/budget_rule.hpp"

namespace rapid {

namespace {

int budget_command(const std::string& dir) {
  const auto curves = check_option("DIR", [&] { return read_reference_curves(dir); });
  int status = kExitOk;
  for (const auto& [scenario, runs] : curves) {
    try {
      std::cout << budget_rule_report(scenario, runs, apply_budget_rule(runs));
    } catch (const std::invalid_argument& e) {
      std::cout << scenario << ": " << e.what() << "\n";
      status = kExitFailed;
    }
  }
  return status;
}

}  // namespace

Command add_budget_command(CLI::App& parent) {
  auto dir = std::make_shared<std::string>();
  CLI::App* sub = parent.add_subcommand(
      "budget", "Apply the flow profile's budget rule to reference DDPG runs: plateau check and budget T");
  sub->add_option("DIR", *dir, "a folder with the reference runs' record.json files (a sweep folder)")->required();
  return {sub, [dir] { return budget_command(*dir); }};
}

}  // namespace rapid
