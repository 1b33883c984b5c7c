// `rapid paper REPORTS_DIR`: the paper beside a reports folder (report/paper_ranking.hpp,
// docs/reports.md §The paper beside us): per row of its Table I that the paper has, the order of
// the methods in the paper and in the folder, Kendall's τ-b and its interval, and the permutation
// test over the rows. The same text as the end of table.md; this reads only summary.json, so it
// also serves a committed folder whose records are not there.
#include <iostream>

#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/paper_ranking.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

namespace {

int paper_command(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "summary.json").string();
  const nlohmann::json summary = check_option("REPORTS_DIR", [&] { return read_summary_document(dir); });
  const std::string md = check_option("REPORTS_DIR", [&] {
    try {
      return paper_agreement_markdown(summary);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument(path + ": a field has the wrong type: " + std::string(e.what()));
    }
  });
  if (md.empty()) {
    std::cout << "no row of " << path << "'s Table I is one of the paper's with " << kMinRankedMethods
              << " or more of its methods: nothing to set beside the paper\n";
    return kExitOk;
  }
  std::cout << md;
  return kExitOk;
}

}  // namespace

Command add_paper_command(CLI::App& parent) {
  auto dir = std::make_shared<std::string>();
  CLI::App* sub = parent.add_subcommand(
      "paper", "How a reports folder's order of the methods agrees with the paper's Table I, row by row (Kendall's tau)");
  sub->add_option("REPORTS_DIR", *dir, "a reports or sweep folder with summary.json")->required();
  return {sub, [dir] { return paper_command(*dir); }};
}

}  // namespace rapid
