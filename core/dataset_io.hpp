// Reading and writing datasets as D4RL-layout HDF5 files (docs/design.md §Datasets).
//
// Layout: flat datasets `observations` (N × obs_dim), `actions` (N × act_dim), `rewards` (N),
// `next_observations` (N × obs_dim) as float32, and `terminals`, `timeouts` (N) as the bool type
// h5py writes (an enum of int8 with FALSE = 0, TRUE = 1), so Python D4RL tooling reads numpy
// bools. Metadata are variable-length UTF-8 string attributes on the root group.
// Arrays are written chunked with Fletcher-32 checksums, so a flipped bit in a stored file is a
// read error instead of a silently different dataset.
//
// HDF5 is not thread-safe as Debian builds it: call these from one thread at a time.
#pragma once

#include <optional>
#include <string>

#include "core/dataset.hpp"

namespace rapid {

// The dimensions the caller's scenario needs; unset members are not checked. `scenario` only
// names the scenario in mismatch messages.
struct DatasetExpectation {
  std::optional<int> obs_dim;
  std::optional<int> act_dim;
  std::string scenario;
};

// Writes atomically: the file is made in memory, then written to a temporary file beside `path`,
// flushed to disk and renamed over `path` (write_file_atomic), so a killed writer never leaves a
// partial file there and a full disk is an error, with the temporary removed. Refuses (DatasetError) an empty
// dataset or one holding NaN/inf, which read_dataset would reject. Throws DatasetError naming
// the path on any I/O failure; the target is then untouched.
void write_dataset(const std::string& path, const Dataset& dataset);

// Reads and validates a D4RL-layout file: every key present, float32 arrays, flags as the bool
// enum or an 8-bit integer (non-zero = true), ranks, one N for all arrays (N > 0), equal
// observation widths, the expected dimensions, and only finite floats. Rewards and flags may be
// stored as N or N × 1. Root string attributes become the metadata (others are ignored).
// Every failure is a DatasetError with a one-line message naming the file and the mismatch.
Dataset read_dataset(const std::string& path, const DatasetExpectation& expect = {});

// What read_dataset checks before it reads the arrays: the file opens as HDF5 (a file cut short
// does not), every key, the types, ranks, one N > 0 for all arrays, the widths and the expected
// dimensions. Cheap (no array is read), so the checksums and values are left to read_dataset.
// Throws DatasetError as read_dataset does.
void check_dataset_layout(const std::string& path, const DatasetExpectation& expect = {});

}  // namespace rapid
