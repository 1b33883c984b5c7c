#include "experiments/report/cell_records.hpp"

#include "experiments/sweep/cell_record.hpp"

namespace rapid {

LoadedRecord load_cell_record(const SweepFolder& folder, const SweepJob& cell) {
  CellRecord r = read_cell_record(folder, cell);
  LoadedRecord out;
  out.result.seed = cell.seed;
  out.result.status = r.status;
  out.hash_checked = r.hash_checked;
  if (r.status != "ok") {
    out.result.error = r.error;
    return out;
  }
  const nlohmann::json& final = (*r.record)["final"];
  out.result.final_return = final["return_mean"].get<double>();
  if (final.contains("episodes") && final["episodes"].is_number_integer())
    out.result.final_episodes = final["episodes"].get<int>();
  if (const auto& timing = (*r.record)["timing"]; timing.is_object() && timing.contains("wall_s") && timing["wall_s"].is_number())
    out.result.wall_s = timing["wall_s"].get<double>();
  out.record = std::move(r.record);
  return out;
}

}  // namespace rapid
