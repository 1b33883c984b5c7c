// `rapid sweep --reuse-datasets FROM`: start a sweep from another sweep's reference agents and
// prior datasets instead of training the references again (the ablation grids share
// paper-flow's). Only what FROM built for this grid's very inputs is taken (the runner's own
// "done" test, asked of FROM with this grid), only where this sweep has nothing yet, and FROM is
// only read.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiments/sweep/state.hpp"

namespace rapid {

struct ReuseReport {
  std::vector<std::string> copied;   // dataset-stage job ids now taken from FROM
  // Dataset-stage job ids whose reference agents alone were taken (FROM has the references but not
  // the datasets, as the committed results/references/ folders do): the sweep collects the data.
  std::vector<std::string> references_only;
  std::vector<std::string> present;  // this sweep already had them: left alone
  std::vector<std::string> stale;    // FROM has none, or built them for other inputs: the sweep builds them
};

// Copies, for each reference and dataset job of `folder`'s graph that FROM has done for the
// same inputs, its dataset folder (datasets/[<point>/]<scenario>/) and both job folders. Each
// folder is copied next to its place and renamed into it, so a failure leaves nothing half
// copied. `source` is FROM opened as a sweep folder (open_sweep_folder), not `folder` itself.
ReuseReport reuse_datasets(const SweepFolder& folder, const SweepFolder& source);

// For `--check-references`: each reference agent `folder` has trained that FROM has done for the
// same inputs, compared file by file (its checkpoints, byte for byte). Returns one line per
// reference that differs or that FROM lacks, and puts the number of identical ones in *identical.
std::vector<std::string> compare_references(const SweepFolder& folder, const SweepFolder& source, int* identical);

}  // namespace rapid
