#include "experiments/sweep/state.hpp"

#include <fstream>

#include "core/atomic_file.hpp"
#include "core/hash.hpp"
#include "core/printable.hpp"
#include "experiments/run/dataset_build.hpp"
#include "experiments/run/job.hpp"
#include "core/json_input.hpp"
#include "experiments/run/provenance.hpp"
#include "experiments/run/run_config.hpp"
#include "experiments/sweep/cell_record.hpp"

namespace rapid {

namespace fs = std::filesystem;

SweepFolder make_sweep_folder(const fs::path& dir, Grid grid) {
  SweepFolder folder;
  folder.dir = dir;
  folder.graph = build_job_graph(grid);
  folder.grid = std::move(grid);
  return folder;
}

SweepFolder open_sweep_folder(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw std::invalid_argument("'" + dir.string() + "' is not a folder");
  const fs::path grid = dir / sweep_files::kGrid;
  if (!fs::is_regular_file(grid))
    throw std::invalid_argument("'" + dir.string() + "' is not a sweep folder (no " + sweep_files::kGrid + ")");
  return make_sweep_folder(dir, load_grid(grid.string()));
}

std::string expected_cell_hash(const SweepFolder& folder, const SweepJob& cell) {
  JobSpec spec;
  spec.scenario = cell.scenario;
  spec.algo = cell.algo;
  spec.seed = cell.seed;
  spec.dataset = cell.dataset;
  if (!cell.dataset.empty()) {
    spec.dataset_path = folder.path(cell_dataset_path(cell)).string();
    if (!fs::is_regular_file(spec.dataset_path))
      throw std::runtime_error("dataset " + cell_dataset_path(cell) + " is missing");
  }
  spec.config = cell_config(folder.grid, cell.scenario, cell.axis, cell.algo);
  return job_config_hash(spec);
}

// The scenario's own reference settings, not the grid's whole "reference" object: another
// scenario's L changes nothing here, so grids that differ only there share references and datasets.
std::string dataset_stage_inputs_hash(const SweepFolder& folder, const SweepJob& job) {
  const ReferenceSettings r = reference_for(folder.grid, job.scenario);
  const nlohmann::json inputs = {
      {"scenario", job.scenario},
      {"config", cell_config(folder.grid, job.scenario, job.axis)},
      {"reference", {{"seed", r.seed}, {"transitions", r.transitions}, {"noise_std", r.noise_std}, {"steps", r.steps}}},
  };
  return fnv1a_hex(inputs.dump());
}

std::optional<nlohmann::json> read_json_file(const fs::path& path) {
  try {
    return read_json_input(path.string());  // bounded: a hostile file cannot hang or crash the reader
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

void write_outcome(const SweepFolder& folder, const SweepJob& job, const Outcome& o) {
  nlohmann::json j = {{"job", job.id()},         {"state", o.state},   {"attempts", o.attempts},
                      {"exit_code", o.exit_code}, {"signal", o.signal}, {"error", o.error}};
  if (!o.inputs_hash.empty()) j["inputs_hash"] = o.inputs_hash;
  if (!o.marker_hash.empty()) j["marker_hash"] = o.marker_hash;
  fs::create_directories(folder.path(job.dir));
  write_file_atomic(folder.path(job.dir + "/" + sweep_files::kOutcome).string(), j.dump(1));
}

std::optional<Outcome> read_outcome(const SweepFolder& folder, const SweepJob& job) {
  const auto j = read_json_file(folder.path(job.dir + "/" + sweep_files::kOutcome));
  if (!j || !j->is_object()) return std::nullopt;
  Outcome o;
  o.state = j->value("state", "");
  o.attempts = j->value("attempts", 0);
  o.exit_code = j->value("exit_code", -1);
  o.signal = j->value("signal", 0);
  o.error = excerpt(j->value("error", ""));
  o.inputs_hash = j->value("inputs_hash", "");
  o.marker_hash = j->value("marker_hash", "");
  return o;
}

namespace {

bool says_ok(const std::optional<nlohmann::json>& j) {
  return j && j->is_object() && j->contains("status") && (*j)["status"] == "ok";
}

std::string marker_config_hash(const std::optional<nlohmann::json>& marker) {
  if (!marker || !marker->is_object() || !marker->contains("config_hash")) return "";
  const auto& h = (*marker)["config_hash"];
  return h.is_string() ? h.get<std::string>() : h.dump();
}

}  // namespace

bool stage_job_ran_for_current_inputs(const SweepFolder& folder, const SweepJob& job) {
  const auto marker = read_json_file(folder.path(job_marker_path(job)));
  if (!says_ok(marker)) return false;
  const auto outcome = read_outcome(folder, job);
  return outcome && outcome->state == "ok" && outcome->inputs_hash == dataset_stage_inputs_hash(folder, job) &&
         outcome->marker_hash == marker_config_hash(marker);
}

bool job_is_done(const SweepFolder& folder, const SweepJob& job) {
  // A cell: the one judgement of its record that status and the reports share.
  if (job.kind == JobKind::kCell) return read_cell_record(folder, job).done();
  return stage_job_ran_for_current_inputs(folder, job) && stage_job_problem(folder, job).empty();
}

std::string stage_job_problem(const SweepFolder& folder, const SweepJob& job) {
  const DatasetFolder datasets(folder.path(datasets_root(job.reference_point())).string(), job.scenario);
  const RunConfig config = run_config_from_json(cell_config(folder.grid, job.scenario, job.axis), job.scenario);
  if (job.kind == JobKind::kReference)
    return reference_problem(datasets, config.steps, reference_for(folder.grid, job.scenario).steps);
  return datasets_problem(datasets, folder.grid.datasets, job.scenario, config);
}

void mark_dataset_stage_done(const SweepFolder& folder, const SweepJob& job, int attempts) {
  Outcome o;
  o.state = "ok";
  o.attempts = attempts;
  o.exit_code = 0;
  o.inputs_hash = dataset_stage_inputs_hash(folder, job);
  o.marker_hash = marker_config_hash(read_json_file(folder.path(job_marker_path(job))));
  write_outcome(folder, job, o);
}

std::string last_log_line(const SweepFolder& folder, const SweepJob& job) {
  // Only the log's last 64 KiB are read: a job's log may be large, and its last line too (an
  // external method's); a line longer than that is shown from where the tail starts, cut short.
  constexpr std::streamoff kTail = 64 * 1024;
  std::ifstream in(folder.path(job.dir + "/" + sweep_files::kLog), std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  const std::streamoff from = size > kTail ? size - kTail : 0;
  in.seekg(from);
  std::string tail(static_cast<std::size_t>(size - from), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  tail.resize(static_cast<std::size_t>(in.gcount()));
  const std::size_t end = tail.find_last_not_of(" \t\r\n");
  if (end == std::string::npos) return "";
  const std::size_t newline = tail.rfind('\n', end);
  const std::size_t begin = newline == std::string::npos ? 0 : newline + 1;
  return excerpt(std::string_view(tail).substr(begin, end + 1 - begin));
}

}  // namespace rapid
