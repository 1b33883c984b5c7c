// `rapid beside NOW BEFORE`: two reports folders of the same rows side by side
// (report/side_by_side.hpp, docs/reports.md §Two reports side by side): a rerun beside the run it
// replaces, the tuned grid beside the defaults. Reads only the two summary.json files, so committed
// folders serve; prints Markdown, or writes it to --out.
#include <filesystem>
#include <iostream>

#include "core/atomic_file.hpp"
#include "experiments/cli/commands.hpp"
#include "experiments/cli/errors.hpp"
#include "experiments/report/side_by_side.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

namespace {

struct BesideOptions {
  std::string now, before, labels, out;
};

int beside_command(const BesideOptions& o) {
  const nlohmann::json now = check_option("NOW", [&] { return read_summary_document(o.now); });
  const nlohmann::json before = check_option("BEFORE", [&] { return read_summary_document(o.before); });
  std::string now_label = std::filesystem::path(o.now).lexically_normal().filename().string();
  std::string before_label = std::filesystem::path(o.before).lexically_normal().filename().string();
  if (!o.labels.empty()) {
    const std::size_t comma = o.labels.find(',');
    check_option("--labels", [&] {
      if (comma == std::string::npos || comma == 0 || comma + 1 == o.labels.size() ||
          o.labels.find(',', comma + 1) != std::string::npos)
        throw std::invalid_argument("wants two names separated by one comma (e.g. tuned,defaults), got '" + o.labels + "'");
      return 0;
    });
    now_label = o.labels.substr(0, comma);
    before_label = o.labels.substr(comma + 1);
  }
  const std::string md = check_option("NOW BEFORE", [&] {
    try {
      return side_by_side_markdown(now, now_label, before, before_label);
    } catch (const nlohmann::json::exception& e) {
      throw std::invalid_argument("a field of a summary.json has the wrong type: " + std::string(e.what()));
    }
  });
  if (o.out.empty()) {
    std::cout << md;
    return kExitOk;
  }
  try {
    write_file_atomic(o.out, md);
  } catch (const FileWriteError& e) {
    throw UsageError("--out: " + std::string(e.what()));  // a folder that is not there, a path that is a folder
  }
  std::cout << "wrote " << o.out << "\n";
  return kExitOk;
}

}  // namespace

Command add_beside_command(CLI::App& parent) {
  auto o = std::make_shared<BesideOptions>();
  CLI::App* sub = parent.add_subcommand(
      "beside", "Two reports folders of the same rows side by side: Table I, IQMs and the decided verdicts that changed");
  sub->add_option("NOW", o->now, "a reports or sweep folder with summary.json (e.g. the tuned grid's)")->required();
  sub->add_option("BEFORE", o->before, "the one to set beside it (e.g. the defaults')")->required();
  sub->add_option("--labels", o->labels, "NOW,BEFORE: the names in the headings (default: the folder names)");
  sub->add_option("--out", o->out, "write the Markdown here instead of printing it");
  return {sub, [o] { return beside_command(*o); }};
}

}  // namespace rapid
