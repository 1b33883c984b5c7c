// Internal to the dataset reader and writer: the D4RL key names, the h5py bool type, and turning
// HDF5's error stack into one readable line. Not installed for other modules (HDF5 headers stay
// private to rapid_core).
#pragma once

#include <H5Cpp.h>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/tensor.hpp"

namespace rapid::h5 {

inline constexpr const char* kObservations = "observations";
inline constexpr const char* kActions = "actions";
inline constexpr const char* kRewards = "rewards";
inline constexpr const char* kNextObservations = "next_observations";
inline constexpr const char* kTerminals = "terminals";
inline constexpr const char* kTimeouts = "timeouts";
inline constexpr std::array<const char*, 6> kAllKeys = {kObservations, kActions,   kRewards,
                                                        kNextObservations, kTerminals, kTimeouts};

// h5py's numpy-bool type: an enum of int8 with members FALSE = 0 and TRUE = 1.
H5::EnumType bool_enum_type();
// `type` is exactly that enum (any byte order).
bool is_bool_enum(hid_t type);

// A short numpy-like name for an HDF5 datatype in messages: float32, int64, uint8, bool, ...
std::string describe_type(hid_t type);

// "shape 3 × 2" (or "a scalar") for an array's dimensions in messages.
std::string shape_text(const std::vector<hsize_t>& dims);

// The innermost description on HDF5's current error stack — the one that says what went wrong,
// e.g. "truncated file: eof = …" — on one line, or `fallback` if the stack is empty. Clears the
// stack.
std::string error_stack_detail(const std::string& fallback);

// Writing (shared by the D4RL and the Minari writers). Arrays are chunked with Fletcher-32
// checksums and carry no creation or modification times, so the same data gives the same bytes.
//
// `rows` × `cols` floats from a column-major cols × rows matrix (the same bytes, row-major) as
// float32 in `group`; cols == 0 writes a 1-D array of `rows` values.
void write_floats(H5::Group& group, const char* key, const float* data, hsize_t rows, hsize_t cols);
// Flags as h5py's bool.
void write_flags(H5::Group& group, const char* key, const std::vector<bool>& flags);
// Variable-length UTF-8, what h5py writes for a Python str, so it reads back as str.
void write_string_attribute(H5::H5Object& object, const std::string& name, const std::string& value);
// A scalar int64 attribute, what h5py writes for a Python int.
void write_int_attribute(H5::H5Object& object, const std::string& name, long long value);
// A group whose object header carries no times either.
H5::Group create_group(H5::Group& parent, const std::string& name);
// A file made in memory (the core driver without a backing store): HDF5 never writes to disk, so
// a full disk is one failed write() in write_file_atomic rather than an error inside HDF5, whose
// clean-up after a close that could not flush crashes (HDF5 1.10: H5Fclose after a failed
// H5Dclose, SIGSEGV).
H5::H5File in_memory_file();
// The bytes HDF5 would write to a file for `file`, which is closed afterwards.
std::string file_image(H5::H5File& file);

// Column of the first NaN/inf in `m` (= the D4RL row), if any.
std::optional<std::size_t> first_non_finite(const Mat& m);
std::optional<std::size_t> first_non_finite(const RowVec& v);

}  // namespace rapid::h5
