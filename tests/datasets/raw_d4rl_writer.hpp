// Writes D4RL-layout files with the HDF5 C API directly, key by key, so a test can make exactly
// one key wrong (missing, another dtype, another shape, a NaN) — files write_dataset never
// produces. It also writes the way other tools may: contiguous (unchunked) arrays and
// fixed-length string attributes.
#pragma once

#include <hdf5.h>

#include <optional>
#include <string>
#include <vector>

#include "core/dataset.hpp"

namespace rapid::testing {

struct KeyEdit {
  std::string key;
  bool omit = false;
  hid_t file_type = -1;              // store as this type (e.g. H5T_IEEE_F64LE); -1 = the D4RL type
  std::vector<hsize_t> dims = {};    // store with this shape (values cut or zero-padded); empty = as is
  std::optional<std::size_t> nan_at = {};  // make this element (flat index) a NaN
};

void write_raw_d4rl(const std::string& path, const Dataset& dataset, const std::vector<KeyEdit>& edits = {});

}  // namespace rapid::testing
