// What the HTML report (report_page.hpp) is made from, read from the files a summary leaves:
// summary.json, runs.csv (every seed's evaluation curve), the figure PNGs and animation GIFs of
// the reports folder, and the sweep folder's grid.json, sweep.json and run records. The page reads
// nothing else, so a committed reports folder (results/*, whose jobs/ is not in git) makes the
// same page as the full sweep folder, less the links to records that are not there.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "experiments/sweep/state.hpp"

namespace rapid {

using SeedCurve = std::vector<std::pair<double, double>>;  // (evaluation target step, return_mean)

// A seed's files, as links relative to the page.
struct SeedFiles {
  std::string record;            // where its record.json is in a full sweep folder
  bool record_present = false;   // whether it is there now
  std::string animation;         // the GIF drawn from this run (animations.hpp), empty if none
};

struct Figure {
  std::string name;      // file stem: figure2, figure3a, figure3b, sensitivity-<key>
  std::string data_uri;  // its PNG, inlined
};

struct ReportFolder {
  std::string name;                        // the reports folder's own name (results/paper-flow-decided: paper-flow-decided)
  nlohmann::json summary;                  // summary.json ("rapid.summary/1")
  SweepFolder sweep;                       // grid.json and the job graph it expands to
  nlohmann::json grid_document;            // grid.json as written (description, profile, budgets)
  std::optional<nlohmann::json> manifest;  // sweep.json: the last `rapid sweep`, when there is one
  std::vector<Figure> figures;             // in the page's order; only those drawn
  std::vector<std::string> animations;     // GIF file names in the reports folder
  bool has_runs_csv = false;
  std::map<std::string, std::map<std::uint64_t, SeedCurve>> seed_curves;  // cell key → seed → curve
  std::map<std::string, std::map<std::uint64_t, SeedFiles>> seed_files;   // cell key → seed → files
  int records_present = 0;
};

// report_dir holds the reports (summary.json, runs.csv, figures), sweep_dir the grid and the
// records (the same folder unless `rapid summarize --out`). Throws std::invalid_argument (one
// line naming the file) when summary.json or grid.json is missing or not what it should be.
ReportFolder read_report_folder(const std::filesystem::path& report_dir, const std::filesystem::path& sweep_dir);

}  // namespace rapid
