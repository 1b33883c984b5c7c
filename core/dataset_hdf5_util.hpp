// Internal to the dataset reader and writer: the D4RL key names, the h5py bool type, and turning
// HDF5's error stack into one readable line. Not installed for other modules (HDF5 headers stay
// private to rapid_core).
#pragma once

#include <H5Cpp.h>

#include <array>
#include <cstddef>
#include <optional>
#include <string>

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

// The innermost description on HDF5's current error stack — the one that says what went wrong,
// e.g. "truncated file: eof = …" — on one line, or `fallback` if the stack is empty. Clears the
// stack.
std::string error_stack_detail(const std::string& fallback);

// Column of the first NaN/inf in `m` (= the D4RL row), if any.
std::optional<std::size_t> first_non_finite(const Mat& m);
std::optional<std::size_t> first_non_finite(const RowVec& v);

}  // namespace rapid::h5
