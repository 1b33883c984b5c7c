#include "experiments/report/cell_records.hpp"

#include <cmath>

#include "experiments/run/record.hpp"

namespace rapid {

namespace {

LoadedRecord not_usable(std::uint64_t seed, std::string status, std::string error) {
  LoadedRecord out;
  out.result.seed = seed;
  out.result.status = std::move(status);
  out.result.error = std::move(error);
  return out;
}

bool names_cell(const nlohmann::json& record, const SweepJob& cell) {
  const nlohmann::json* c = record.contains("cell") ? &record["cell"] : nullptr;
  if (!c || !c->is_object()) return false;
  const nlohmann::json dataset = cell.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(cell.dataset);
  return c->value("scenario", "") == cell.scenario && c->value("algo", "") == cell.algo &&
         c->contains("seed") && (*c)["seed"] == cell.seed && c->contains("dataset") && (*c)["dataset"] == dataset;
}

}  // namespace

LoadedRecord load_cell_record(const SweepFolder& folder, const SweepJob& cell) {
  const auto path = folder.path(job_marker_path(cell));
  if (!std::filesystem::exists(path)) return not_usable(cell.seed, "missing", "no record yet");
  const auto parsed = read_json_file(path);
  if (!parsed || !parsed->is_object()) return not_usable(cell.seed, "corrupt", "record.json is not a JSON object");
  const nlohmann::json& record = *parsed;
  if (record.value("schema", "") != kRunRecordSchema)
    return not_usable(cell.seed, "corrupt", std::string("record.json: schema is not ") + kRunRecordSchema);
  if (!names_cell(record, cell)) return not_usable(cell.seed, "corrupt", "record.json names another cell");

  const std::string status = record.value("status", "");
  if (status != "ok") {
    const std::string error = record.contains("error") && record["error"].is_string() ? record["error"].get<std::string>() : "";
    if (status == "failed" || status == "diverged") return not_usable(cell.seed, status, error);
    return not_usable(cell.seed, "corrupt", "record.json: unknown status '" + status + "'");
  }
  const nlohmann::json* final_mean = record.contains("final") && record["final"].is_object() && record["final"].contains("return_mean")
                                         ? &record["final"]["return_mean"]
                                         : nullptr;
  if (!final_mean || !final_mean->is_number() || !std::isfinite(final_mean->get<double>()))
    return not_usable(cell.seed, "corrupt", "record.json: ok but final.return_mean is not a finite number");

  LoadedRecord out;
  out.result.seed = cell.seed;
  try {
    const std::string expected = expected_cell_hash(folder, cell);
    if (record.value("config_hash", "") != expected)
      return not_usable(cell.seed, "stale", "config hash differs from the grid's (rerun `rapid sweep`)");
  } catch (const std::runtime_error&) {
    out.hash_checked = false;  // the dataset is gone; the record is the only witness left
  }
  out.result.status = "ok";
  out.result.final_return = final_mean->get<double>();
  out.record = record;
  return out;
}

}  // namespace rapid
