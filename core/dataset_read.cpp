// read_dataset: open a D4RL-layout HDF5 file and check everything before trusting it. The checks
// run in the order a user would fix them (missing key, dtype, shape, dimensions, values), and
// each one stops with a message naming the key and what was expected.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "core/dataset_hdf5_util.hpp"
#include "core/dataset_io.hpp"

namespace rapid {

namespace {

// One array of the file, opened but not yet read.
struct StoredArray {
  H5::DataSet ds;
  std::vector<hsize_t> dims;
  hsize_t rows() const { return dims.empty() ? 0 : dims[0]; }
  hsize_t cols() const { return dims.size() < 2 ? 1 : dims[1]; }
};

// The six arrays, opened but not yet read.
struct StoredArrays {
  StoredArray obs, act, rew, next_obs, term, tout;
};

class Reader {
 public:
  Reader(const std::string& path, const DatasetExpectation& expect) : path_(path), expect_(expect) {}

  // The file's structure and sizes, from metadata alone: nothing is read yet.
  StoredArrays check() {
    open_file();
    require_all_keys();
    return check_layout();
  }

  Dataset read() {
    const StoredArrays a = check();
    Dataset d = load(a);
    // NaN/inf would poison every critic target that samples them (even 0 · NaN is NaN).
    require_finite(h5::kObservations, h5::first_non_finite(d.observations));
    require_finite(h5::kActions, h5::first_non_finite(d.actions));
    require_finite(h5::kRewards, h5::first_non_finite(d.rewards));
    require_finite(h5::kNextObservations, h5::first_non_finite(d.next_observations));
    d.metadata = read_string_attributes();
    return d;
  }

  DatasetError fail(const std::string& what) const { return DatasetError("dataset " + path_ + ": " + what); }

 private:
  // Types, ranks, row counts and widths, from metadata alone: nothing is read yet.
  StoredArrays check_layout() {
    StoredArrays a{open_array(h5::kObservations),     open_array(h5::kActions),
                   open_array(h5::kRewards),          open_array(h5::kNextObservations),
                   open_array(h5::kTerminals),        open_array(h5::kTimeouts)};
    struct Keyed {
      const char* key;
      const StoredArray* array;
    };
    const Keyed floats[] = {{h5::kObservations, &a.obs}, {h5::kActions, &a.act}, {h5::kRewards, &a.rew},
                            {h5::kNextObservations, &a.next_obs}};
    const Keyed flags[] = {{h5::kTerminals, &a.term}, {h5::kTimeouts, &a.tout}};
    const Keyed vectors[] = {{h5::kRewards, &a.rew}, {h5::kTerminals, &a.term}, {h5::kTimeouts, &a.tout}};
    const Keyed after_obs[] = {{h5::kActions, &a.act},
                               {h5::kRewards, &a.rew},
                               {h5::kNextObservations, &a.next_obs},
                               {h5::kTerminals, &a.term},
                               {h5::kTimeouts, &a.tout}};

    for (const Keyed& k : floats) require_float32(k.key, *k.array);
    for (const Keyed& k : flags) require_flag_type(k.key, *k.array);

    require_matrix(h5::kObservations, a.obs, "obs_dim");
    require_matrix(h5::kActions, a.act, "act_dim");
    require_matrix(h5::kNextObservations, a.next_obs, "obs_dim");
    for (const Keyed& k : vectors) require_vector(k.key, *k.array);

    const hsize_t n = a.obs.rows();
    for (const Keyed& k : after_obs)
      if (k.array->rows() != n)
        throw fail("'" + std::string(k.key) + "' has " + std::to_string(k.array->rows()) +
                   " rows, 'observations' has " + std::to_string(n));
    if (n == 0) throw fail("holds no transitions");
    if (a.next_obs.cols() != a.obs.cols())
      throw fail("'next_observations' has " + std::to_string(a.next_obs.cols()) + " columns, 'observations' has " +
                 std::to_string(a.obs.cols()));
    require_width(h5::kObservations, a.obs.cols(), expect_.obs_dim);
    require_width(h5::kActions, a.act.cols(), expect_.act_dim);
    return a;
  }

  Dataset load(const StoredArrays& a) const {
    Dataset d;
    const auto n = static_cast<Eigen::Index>(a.obs.rows());
    d.observations.resize(static_cast<Eigen::Index>(a.obs.cols()), n);
    d.actions.resize(static_cast<Eigen::Index>(a.act.cols()), n);
    d.rewards.resize(n);
    d.next_observations.resize(static_cast<Eigen::Index>(a.next_obs.cols()), n);
    read_floats(h5::kObservations, a.obs, d.observations.data());
    read_floats(h5::kActions, a.act, d.actions.data());
    read_floats(h5::kRewards, a.rew, d.rewards.data());
    read_floats(h5::kNextObservations, a.next_obs, d.next_observations.data());
    d.terminals = read_flags(h5::kTerminals, a.term);
    d.timeouts = read_flags(h5::kTimeouts, a.tout);
    return d;
  }

  void open_file() {
    const htri_t is_hdf5 = H5Fis_hdf5(path_.c_str());
    if (is_hdf5 == 0) throw fail("not an HDF5 file");
    if (is_hdf5 < 0) throw fail("cannot open: " + h5::error_stack_detail("not readable"));
    file_ = H5::H5File(path_, H5F_ACC_RDONLY);  // a truncated file throws here
  }

  void require_all_keys() {
    std::string missing;
    int count = 0;
    for (const char* key : h5::kAllKeys) {
      if (H5Lexists(file_.getId(), key, H5P_DEFAULT) > 0) {
        if (file_.childObjType(key) != H5O_TYPE_DATASET)
          throw fail("'" + std::string(key) + "' is not an array (a group?)");
        continue;
      }
      missing += (count++ ? ", '" : "'") + std::string(key) + "'";
    }
    if (count == 1) throw fail("missing key " + missing);
    if (count > 1) throw fail("missing keys " + missing);
  }

  StoredArray open_array(const char* key) {
    StoredArray a{file_.openDataSet(key), {}};
    const H5::DataSpace space = a.ds.getSpace();
    a.dims.resize(static_cast<std::size_t>(space.getSimpleExtentNdims()));
    if (!a.dims.empty()) space.getSimpleExtentDims(a.dims.data());
    return a;
  }

  void require_float32(const char* key, const StoredArray& a) const {
    const H5::DataType type = a.ds.getDataType();
    if (H5Tget_class(type.getId()) != H5T_FLOAT || type.getSize() != 4)
      throw fail("'" + std::string(key) + "' is " + h5::describe_type(type.getId()) + ", expected float32");
  }

  void require_flag_type(const char* key, const StoredArray& a) const {
    const H5::DataType type = a.ds.getDataType();
    const bool byte_integer = H5Tget_class(type.getId()) == H5T_INTEGER && type.getSize() == 1;
    if (!byte_integer && !h5::is_bool_enum(type.getId()))
      throw fail("'" + std::string(key) + "' is " + h5::describe_type(type.getId()) +
                 ", expected bool (h5py's int8 enum) or an 8-bit integer");
  }

  void require_matrix(const char* key, const StoredArray& a, const char* width_name) const {
    if (a.dims.size() != 2)
      throw fail("'" + std::string(key) + "' has " + h5::shape_text(a.dims) + ", expected 2-D (N × " + width_name + ")");
  }

  void require_vector(const char* key, const StoredArray& a) const {
    if (a.dims.size() == 1 || (a.dims.size() == 2 && a.dims[1] == 1)) return;
    throw fail("'" + std::string(key) + "' has " + h5::shape_text(a.dims) + ", expected N or N × 1");
  }

  void require_width(const char* key, hsize_t cols, std::optional<int> expected) const {
    if (cols == 0) throw fail("'" + std::string(key) + "' has 0 columns");
    if (!expected || cols == static_cast<hsize_t>(*expected)) return;
    const std::string who = expect_.scenario.empty() ? "expected" : "scenario " + expect_.scenario + " expects";
    throw fail("'" + std::string(key) + "' has " + std::to_string(cols) + " columns, " + who + " " +
               std::to_string(*expected));
  }

  // Through the C API: the C++ wrapper clears the error stack that says *why* a read failed
  // (e.g. a Fletcher-32 checksum mismatch).
  void read_raw(const char* key, const StoredArray& a, hid_t memory_type, void* out) const {
    if (H5Dread(a.ds.getId(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0)
      throw fail("cannot read '" + std::string(key) + "' (corrupt file?): " + h5::error_stack_detail("read failed"));
  }

  void read_floats(const char* key, const StoredArray& a, float* out) const {
    read_raw(key, a, H5T_NATIVE_FLOAT, out);
  }

  std::vector<bool> read_flags(const char* key, const StoredArray& a) const {
    // The file's own type in native byte order: bytes as stored, 0 = false. (HDF5 converts
    // neither enum ↔ integer nor a signed byte to unsigned without clamping.)
    const H5::DataType file_type = a.ds.getDataType();
    const hid_t memory_type = H5Tget_native_type(file_type.getId(), H5T_DIR_ASCEND);
    std::vector<std::uint8_t> bytes(a.rows());
    try {
      read_raw(key, a, memory_type, bytes.data());
    } catch (...) {
      H5Tclose(memory_type);
      throw;
    }
    H5Tclose(memory_type);
    return std::vector<bool>(bytes.begin(), bytes.end());
  }

  void require_finite(const char* key, std::optional<std::size_t> row) const {
    if (row) throw fail("'" + std::string(key) + "' has a non-finite value (NaN or inf) at row " + std::to_string(*row));
  }

  // Scalar string attributes of the root group; numbers and arrays some tools add are skipped.
  Metadata read_string_attributes() const {
    Metadata out;
    const H5::Group root = file_.openGroup("/");
    const int count = root.getNumAttrs();
    for (int i = 0; i < count; ++i) {
      const H5::Attribute attr = root.openAttribute(static_cast<unsigned>(i));
      if (attr.getTypeClass() != H5T_STRING || attr.getSpace().getSimpleExtentNpoints() != 1) continue;
      std::string value;
      attr.read(attr.getStrType(), value);
      while (!value.empty() && value.back() == '\0') value.pop_back();  // fixed-length padding
      out[attr.getName()] = value;
    }
    return out;
  }

  std::string path_;
  DatasetExpectation expect_;
  H5::H5File file_;
};

// Runs `use` on a Reader of `path`, with the checks and the error that both entry points share.
template <typename Use>
auto with_reader(const std::string& path, const DatasetExpectation& expect, Use use) {
  H5::Exception::dontPrint();  // errors become exceptions with our message, not stderr dumps
  Reader reader(path, expect);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw reader.fail("no such file");
  if (std::filesystem::is_directory(path, ec)) throw reader.fail("is a directory, not an HDF5 file");
  try {
    return use(reader);
  } catch (const H5::Exception& e) {
    // Opening a truncated file lands here ("truncated file: eof = …, stored_eof = …").
    throw reader.fail("unreadable HDF5 file (" + h5::error_stack_detail(e.getDetailMsg()) + ")");
  }
}

}  // namespace

Dataset read_dataset(const std::string& path, const DatasetExpectation& expect) {
  return with_reader(path, expect, [](Reader& r) { return r.read(); });
}

void check_dataset_layout(const std::string& path, const DatasetExpectation& expect) {
  with_reader(path, expect, [](Reader& r) { r.check(); });
}

}  // namespace rapid
