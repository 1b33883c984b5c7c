#include "core/dataset_hdf5_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

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

// Chunks of about 256 KiB: large enough for fast sequential reads, small enough that the
// Fletcher-32 checksum pinpoints damage.
constexpr hsize_t kChunkBytes = 256 * 1024;

H5::DSetCreatPropList checksummed_chunks(int rank, const hsize_t* dims, std::size_t element_bytes) {
  const hsize_t row_bytes = (rank == 2 ? dims[1] : 1) * element_bytes;
  hsize_t chunk[2] = {std::clamp<hsize_t>(kChunkBytes / row_bytes, 1, dims[0]), rank == 2 ? dims[1] : 1};
  H5::DSetCreatPropList plist;
  plist.setChunk(rank, chunk);
  plist.setFletcher32();
  // No creation/modification times in the object headers: the same data must give the same
  // bytes, since a cell's config hash covers its dataset file.
  H5Pset_obj_track_times(plist.getId(), false);
  return plist;
}

// How much the in-memory file grows at a time.
constexpr std::size_t kImageIncrement = 1 << 20;

}  // namespace

void write_floats(H5::Group& group, const char* key, const float* data, hsize_t rows, hsize_t cols) {
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {rows, cols};
  H5::DataSpace space(rank, dims);
  H5::DataSet ds = group.createDataSet(key, H5::PredType::IEEE_F32LE, space, checksummed_chunks(rank, dims, 4));
  ds.write(data, H5::PredType::NATIVE_FLOAT);
}

void write_flags(H5::Group& group, const char* key, const std::vector<bool>& flags) {
  const std::vector<std::int8_t> bytes(flags.begin(), flags.end());
  const hsize_t dims[1] = {bytes.size()};
  H5::DataSpace space(1, dims);
  const H5::EnumType type = bool_enum_type();
  H5::DataSet ds = group.createDataSet(key, type, space, checksummed_chunks(1, dims, 1));
  ds.write(bytes.data(), type);
}

void write_string_attribute(H5::H5Object& object, const std::string& name, const std::string& value) {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  H5::Attribute attr = object.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attr.write(type, value);
}

void write_int_attribute(H5::H5Object& object, const std::string& name, long long value) {
  const std::int64_t v = value;
  H5::Attribute attr = object.createAttribute(name, H5::PredType::STD_I64LE, H5::DataSpace(H5S_SCALAR));
  attr.write(H5::PredType::NATIVE_INT64, &v);
}

H5::Group create_group(H5::Group& parent, const std::string& name) {
  const hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, false);  // as for arrays: the same data, the same bytes
  const hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  if (id < 0) throw H5::GroupIException("H5Gcreate2", "cannot create group " + name);
  H5::Group group(id);
  H5Gclose(id);  // H5::Group(id) took its own reference
  return group;
}

H5::H5File in_memory_file() {
  H5::FileAccPropList in_memory;
  H5Pset_fapl_core(in_memory.getId(), kImageIncrement, /*backing_store=*/false);
  // HDF5 first tries to open the name as an existing file; under /dev/null none can exist, so
  // nothing on disk is touched.
  return H5::H5File("/dev/null/rapid-in-memory.h5", H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, in_memory);
}

std::string file_image(H5::H5File& file) {
  file.flush(H5F_SCOPE_GLOBAL);
  const ssize_t size = H5Fget_file_image(file.getId(), nullptr, 0);
  std::string image(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
  if (size <= 0 || H5Fget_file_image(file.getId(), image.data(), image.size()) != size)
    throw H5::FileIException("H5Fget_file_image", "cannot take the file's image");
  file.close();
  return image;
}

std::string shape_text(const std::vector<hsize_t>& dims) {
  if (dims.empty()) return "a scalar";
  std::string s;
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? " × " : "") + std::to_string(dims[i]);
  return "shape " + s;
}

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
