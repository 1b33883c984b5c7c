#include "experiments/run/prior_dataset.hpp"

#include "core/dataset_io.hpp"

namespace rapid {

Dataset read_prior_dataset(const std::string& path, const std::string& scenario, int obs_dim, int act_dim,
                           const Algorithm& algo) {
  Dataset data = read_dataset(path, {obs_dim, act_dim, scenario});
  // Every environment's action box is [-1, 1]; data outside it came from another task.
  const float max_abs = data.actions.cwiseAbs().maxCoeff();
  if (max_abs > 1.0f)
    throw DatasetError("dataset " + path + ": actions must lie in [-1, 1], found |a| = " + std::to_string(max_abs));
  // Two scenarios may share dimensions; a file that names its scenario must name this one.
  const auto named = data.metadata.find(meta::kScenario);
  if (named != data.metadata.end() && named->second != scenario)
    throw DatasetError("dataset " + path + ": built for scenario '" + named->second + "', not '" + scenario + "'");
  // Returns over the next decisions stop at an episode's end; one unbroken stream has none.
  if (algo.uses_returns && !data.has_episode_ends())
    throw DatasetError("dataset " + path + ": has no episode ends (terminals/timeouts all false); " + algo.name +
                       " needs episodes");
  return data;
}

}  // namespace rapid
