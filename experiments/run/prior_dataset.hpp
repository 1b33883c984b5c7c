// The prior data a job trains on (docs/datasets.md): a D4RL-layout file checked against the job's
// scenario. `rapid run` checks it before it writes anything (a file that does not fit is bad
// input, exit 2) and the job reads it through the same function, so the two cannot disagree.
#pragma once

#include <string>

#include "algos/registry.hpp"
#include "core/dataset.hpp"

namespace rapid {

// Reads `path` and checks it fits `scenario` and `algo`: everything read_dataset checks (keys,
// dtypes, shapes, finite values) with the scenario's dimensions, every action inside the [-1, 1]
// box, when the file says which scenario it was built for, that it is this one, and, for an
// algorithm that uses returns over episodes, that some transition ends an episode. Throws
// DatasetError, one line naming the file.
Dataset read_prior_dataset(const std::string& path, const std::string& scenario, int obs_dim, int act_dim,
                           const Algorithm& algo);

}  // namespace rapid
