#include "core/dataset_hdf5_util.hpp"

#include <cstdint>
#include <cmath>

namespace rapid::h5 {

H5::EnumType bool_enum_type() {
  H5::EnumType type(H5::PredType::NATIVE_INT8);
  std::int8_t no = 0, yes = 1;  // HDF5 1.10's insert() takes a non-const pointer
  type.insert("FALSE", &no);
  type.insert("TRUE", &yes);
  return type;
}

bool is_bool_enum(hid_t type) {
  if (H5Tget_class(type) != H5T_ENUM || H5Tget_size(type) != 1 || H5Tget_nmembers(type) != 2) return false;
  // Compare values through the member names, so the check does not depend on member order.
  std::int8_t no = -1, yes = -1;
  if (H5Tenum_valueof(type, "FALSE", &no) < 0 || H5Tenum_valueof(type, "TRUE", &yes) < 0) {
    H5Eclear2(H5E_DEFAULT);
    return false;
  }
  return no == 0 && yes == 1;
}

std::string describe_type(hid_t type) {
  const std::size_t bits = 8 * H5Tget_size(type);
  switch (H5Tget_class(type)) {
    case H5T_FLOAT:
      return "float" + std::to_string(bits);
    case H5T_INTEGER:
      return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
    case H5T_ENUM: {
      if (is_bool_enum(type)) return "bool";
      const hid_t base = H5Tget_super(type);
      const std::string base_name = describe_type(base);
      H5Tclose(base);
      return "an enum of " + base_name;
    }
    case H5T_STRING:
      return "string";
    case H5T_COMPOUND:
      return "a compound type";
    default:
      return "an unsupported HDF5 type";
  }
}

namespace {

herr_t keep_innermost(unsigned /*depth*/, const H5E_error2_t* error, void* out) {
  if (error->desc && *error->desc) *static_cast<std::string*>(out) = error->desc;
  return 0;
}

// HDF5 messages may span lines (e.g. "time = …\n, name = …"); the CLI contract is one line.
std::string one_line(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool space = c == '\n' || c == '\r' || c == '\t' || c == ' ';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out += space ? ' ' : c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace

std::string error_stack_detail(const std::string& fallback) {
  std::string innermost;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, keep_innermost, &innermost);
  H5Eclear2(H5E_DEFAULT);
  return one_line(innermost.empty() ? fallback : innermost);
}

std::optional<std::size_t> first_non_finite(const Mat& m) {
  if (m.allFinite()) return std::nullopt;
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    if (!m.col(c).allFinite()) return static_cast<std::size_t>(c);
  return std::nullopt;
}

std::optional<std::size_t> first_non_finite(const RowVec& v) {
  if (v.allFinite()) return std::nullopt;
  for (Eigen::Index c = 0; c < v.size(); ++c)
    if (!std::isfinite(v[c])) return static_cast<std::size_t>(c);
  return std::nullopt;
}

}  // namespace rapid::h5
