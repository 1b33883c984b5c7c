// `rapid`: the harness's one command line. See docs/design.md §Command line and docs/usage.md.
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "core/printable.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rapid: reproduction harness for RAPID-RL (selective imitation from prior data)"};
  app.require_subcommand(1);
  const std::vector<rapid::Command> commands = {
      rapid::add_rollout_command(app),
      rapid::add_dataset_command(app),
      rapid::add_run_command(app),
      rapid::add_sweep_command(app),
      rapid::add_status_command(app),
      rapid::add_summarize_command(app),
      rapid::add_diff_command(app),
      rapid::add_bench_command(app),
      rapid::add_budget_command(app),
      rapid::add_recheck_command(app),
      rapid::add_simulate_decide_command(app),
      rapid::add_replay_decide_command(app),
      rapid::add_eval_budget_command(app),
      rapid::add_paper_command(app),
      rapid::add_beside_command(app),
      rapid::add_tune_command(app),
      rapid::add_rerun_command(app),
  };

  // CLI11 answers `rapid frobnicate` with "A subcommand is required"; name the unknown one.
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const rapid::Command& command : commands) {
      known = known || command.app->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + command.app->get_name();
    }
    if (!known) {
      std::cerr << "rapid: error: unknown subcommand '" << argv[1] << "'; expected one of " << names << "\n";
      return rapid::kExitUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "rapid: error: " << e.what() << "\n";
    return rapid::kExitUsage;
  }
  for (const rapid::Command& command : commands) {
    if (!command.app->parsed()) continue;
    try {
      const int status = command.run();
      // What a command printed is its output: a pipe closed early or a full disk is a failure, not
      // exit 0 with nothing written (issue #67: `rapid status … > /dev/full` said 0).
      if (!std::cout.flush()) {
        std::cerr << "rapid: failed: could not write standard output: " << std::strerror(errno) << "\n";
        return status == rapid::kExitOk ? rapid::kExitFailed : status;
      }
      return status;
    } catch (const rapid::UsageError& e) {
      std::cerr << "rapid: error: " << rapid::printable(e.what()) << "\n";
      return rapid::kExitUsage;
    } catch (const std::exception& e) {
      std::cerr << "rapid: failed: " << rapid::printable(e.what()) << "\n";
      return rapid::kExitFailed;
    }
  }
  return rapid::kExitUsage;
}
