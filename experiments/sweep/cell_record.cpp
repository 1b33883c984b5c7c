#include "experiments/sweep/cell_record.hpp"

#include <cmath>

#include "core/printable.hpp"
#include "experiments/run/record.hpp"

namespace rapid {

namespace {

bool names_cell(const nlohmann::json& record, const SweepJob& cell) {
  const nlohmann::json* c = record.contains("cell") ? &record["cell"] : nullptr;
  if (!c || !c->is_object()) return false;
  const nlohmann::json dataset = cell.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(cell.dataset);
  return c->value("scenario", nlohmann::json()) == cell.scenario && c->value("algo", nlohmann::json()) == cell.algo &&
         c->contains("seed") && (*c)["seed"] == cell.seed && c->contains("dataset") && (*c)["dataset"] == dataset;
}

std::string text_field(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}

}  // namespace

std::optional<std::string> record_problem(const nlohmann::json& record, const SweepJob& cell) {
  if (!record.is_object()) return "record.json is not a JSON object";
  if (text_field(record, "schema") != kRunRecordSchema)
    return std::string("record.json: schema is not ") + kRunRecordSchema;
  if (!names_cell(record, cell)) return "record.json names another cell";
  if (!record.contains("config_hash") || !record["config_hash"].is_string()) return "record.json: no config_hash";
  const std::string status = text_field(record, "status");
  if (status != "ok" && status != "failed" && status != "diverged")
    return "record.json: unknown status '" + status + "'";
  if (status != "ok") return std::nullopt;
  const nlohmann::json* final_mean = record.contains("final") && record["final"].is_object() &&
                                             record["final"].contains("return_mean")
                                         ? &record["final"]["return_mean"]
                                         : nullptr;
  if (!final_mean || !final_mean->is_number() || !std::isfinite(final_mean->get<double>()))
    return "record.json: ok but final.return_mean is not a finite number";
  return std::nullopt;
}

CellRecord read_cell_record(const SweepFolder& folder, const SweepJob& cell) {
  CellRecord out;
  const auto path = folder.path(job_marker_path(cell));
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    out.status = "missing";
    out.error = "no record yet";
    return out;
  }
  const auto parsed = read_json_file(path);
  const std::optional<std::string> problem =
      parsed ? record_problem(*parsed, cell) : std::optional<std::string>("record.json is not valid JSON");
  if (problem) {
    out.status = "corrupt";
    out.error = *problem;
    return out;
  }
  out.record = parsed;
  out.status = text_field(*parsed, "status");
  out.error = excerpt(text_field(*parsed, "error"));
  try {
    if ((*parsed)["config_hash"].get<std::string>() != expected_cell_hash(folder, cell)) {
      out.status = "stale";
      out.error = "config hash differs from the grid's (rerun `rapid sweep`)";
    }
  } catch (const std::runtime_error&) {
    out.hash_checked = false;  // the dataset is gone: the record cannot be checked
  }
  // A run is ok only when the attempt that wrote its record is (issue #67): an external command may
  // write a valid record and then exit 1. The outcome is of the last attempt (restored records have
  // none). An attempt refused as bad input (exit 2) or killed wrote no record: an ok one is older.
  if (out.status == "ok")
    if (const std::optional<Outcome> o = read_outcome(folder, cell); o && o->state == "failed" && o->exit_code == 1) {
      out.status = "failed";
      out.error = "its record says ok, but the attempt that wrote it failed: " + o->error;
    }
  return out;
}

}  // namespace rapid
