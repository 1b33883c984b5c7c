#include "experiments/report/report_folder.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "experiments/report/html_text.hpp"
#include "experiments/report/summary.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

nlohmann::json read_json_or_throw(const fs::path& path, const std::string& what) {
  if (!fs::is_regular_file(path)) throw std::invalid_argument(path.string() + ": no " + what + " here");
  const auto j = read_json_file(path);
  if (!j) throw std::invalid_argument(path.string() + ": not valid JSON");
  return *j;
}

// A line of runs.csv split at its commas; a field in double quotes (an axis value that is a
// list) keeps its commas (tables.cpp writes it so).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.emplace_back();
    else fields.back() += c;
  }
  return fields;
}

// runs.csv's identity of a job's lines: scenario, dataset, algo and one field per grid axis.
std::string runs_identity(const SweepJob& job, const Grid& grid) {
  std::string id = job.scenario + "," + (job.dataset.empty() ? sweep_files::kNoDataset : job.dataset) + "," + job.algo;
  for (const GridAxis& axis : grid.axes) {
    id += ",";
    for (const auto& [key, value] : job.axis)
      if (key == axis.key) id += axis_value_label(value);
  }
  return id + "," + std::to_string(job.seed);
}

// runs.csv into per-seed curves, keyed like the jobs; lines of no job of the grid are ignored.
void read_seed_curves(const fs::path& path, ReportFolder& folder) {
  std::map<std::string, const SweepJob*> by_identity;
  for (const SweepJob& job : folder.sweep.graph.jobs)
    if (job.kind == JobKind::kCell) by_identity[runs_identity(job, folder.sweep.grid)] = &job;
  std::istringstream lines(read_file(path.string()));
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    std::vector<std::string> f = csv_fields(line);
    if (f.size() < 5) continue;
    const std::string ret = f.back();
    f.pop_back();
    const std::string step = f.back();
    f.pop_back();
    std::string identity;
    for (const std::string& x : f) identity += (identity.empty() ? "" : ",") + x;
    const auto job = by_identity.find(identity);
    if (job == by_identity.end()) continue;
    try {
      folder.seed_curves[cell_key(*job->second)][job->second->seed].emplace_back(std::stod(step), std::stod(ret));
    } catch (const std::exception&) {
      throw std::invalid_argument(path.string() + ": not a number in line '" + line + "'");
    }
  }
}

// Figures 2, 3(a), 3(b), then the sensitivity figures by name: those scripts/plot drew.
void read_figures(const fs::path& dir, ReportFolder& folder) {
  std::vector<std::string> names = {"figure2", "figure3a", "figure3b"};
  std::vector<std::string> sensitivity;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string file = e.path().filename().string();
    if (file.rfind("sensitivity-", 0) == 0 && e.path().extension() == ".png") sensitivity.push_back(e.path().stem().string());
  }
  std::sort(sensitivity.begin(), sensitivity.end());
  names.insert(names.end(), sensitivity.begin(), sensitivity.end());
  for (const std::string& name : names) {
    const fs::path png = dir / (name + ".png");
    if (fs::is_regular_file(png)) folder.figures.push_back({name, data_uri("image/png", read_file(png.string()))});
  }
}

// The GIFs of the folder, and the run each was drawn from: its trace names the policy,
// SWEEP/<job dir>/actor.ckpt (animations.cpp).
void read_animations(const fs::path& dir, ReportFolder& folder) {
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string file = e.path().filename().string();
    if (file.rfind("animation-", 0) == 0 && e.path().extension() == ".gif") folder.animations.push_back(file);
  }
  std::sort(folder.animations.begin(), folder.animations.end());
  for (const std::string& gif : folder.animations) {
    const auto trace = read_json_file(dir / (gif.substr(0, gif.size() - 4) + ".trace.json"));
    if (!trace || !trace->contains("policy") || !(*trace)["policy"].is_string()) continue;
    const std::string policy = (*trace)["policy"];
    for (const SweepJob& job : folder.sweep.graph.jobs) {
      const std::string tail = "/" + job.dir + "/actor.ckpt";
      if (job.kind == JobKind::kCell && policy.size() >= tail.size() &&
          policy.compare(policy.size() - tail.size(), tail.size(), tail) == 0)
        folder.seed_files[cell_key(job)][job.seed].animation = gif;
    }
  }
}

}  // namespace

ReportFolder read_report_folder(const fs::path& report_dir, const fs::path& sweep_dir) {
  ReportFolder folder;
  folder.name = fs::absolute(report_dir).lexically_normal().filename().string();
  if (folder.name.empty()) folder.name = fs::absolute(report_dir).lexically_normal().parent_path().filename().string();  // "dir/"
  folder.summary = read_json_or_throw(report_dir / "summary.json", "summary.json (run rapid summarize first)");
  if (!folder.summary.is_object() || folder.summary.value("schema", "") != kSummarySchema)
    throw std::invalid_argument((report_dir / "summary.json").string() + ": not a " + kSummarySchema + " document");
  folder.grid_document = read_json_or_throw(sweep_dir / sweep_files::kGrid, "grid.json");
  folder.sweep = open_sweep_folder(sweep_dir);
  folder.manifest = read_json_file(sweep_dir / sweep_files::kManifest);

  // Links from the page to the sweep's files: relative, so the folder can move.
  const fs::path to_sweep = fs::absolute(sweep_dir).lexically_normal().lexically_relative(fs::absolute(report_dir).lexically_normal());
  for (const SweepJob& job : folder.sweep.graph.jobs) {
    if (job.kind != JobKind::kCell) continue;
    SeedFiles& files = folder.seed_files[cell_key(job)][job.seed];
    files.record = (to_sweep / job.dir / "record.json").lexically_normal().generic_string();
    files.record_present = fs::is_regular_file(folder.sweep.path(job.dir) / "record.json");
    folder.records_present += files.record_present ? 1 : 0;
  }
  const fs::path runs = report_dir / "runs.csv";
  folder.has_runs_csv = fs::is_regular_file(runs);
  if (folder.has_runs_csv) read_seed_curves(runs, folder);
  read_figures(report_dir, folder);
  read_animations(report_dir, folder);
  return folder;
}

}  // namespace rapid
