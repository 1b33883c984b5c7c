// `rapid dataset export` and `rapid dataset import` (cmd_dataset_minari.cpp), registered by
// `rapid dataset` (cmd_dataset.cpp).
#pragma once

#include "experiments/cli/commands.hpp"

namespace rapid {

Command add_export(CLI::App& dataset);
Command add_import(CLI::App& dataset);

}  // namespace rapid
