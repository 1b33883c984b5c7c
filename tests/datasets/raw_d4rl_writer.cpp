#include "tests/datasets/raw_d4rl_writer.hpp"

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace rapid::testing {

namespace {

void check(herr_t status, const char* what) {
  if (status < 0) throw std::runtime_error(std::string("raw HDF5 writer: ") + what + " failed");
}

const KeyEdit* edit_for(const std::vector<KeyEdit>& edits, const std::string& key) {
  for (const KeyEdit& e : edits)
    if (e.key == key) return &e;
  return nullptr;
}

// h5py's bool, built here independently of the production code.
hid_t make_bool_enum() {
  const hid_t type = H5Tenum_create(H5T_NATIVE_INT8);
  std::int8_t no = 0, yes = 1;
  check(H5Tenum_insert(type, "FALSE", &no), "enum insert");
  check(H5Tenum_insert(type, "TRUE", &yes), "enum insert");
  return type;
}

template <class T>
void write_array(hid_t file, const std::string& key, std::vector<T> values, std::vector<hsize_t> dims,
                 hid_t default_file_type, hid_t memory_type, const KeyEdit* edit) {
  if (edit && edit->omit) return;
  hid_t file_type = default_file_type;
  if (edit && edit->file_type >= 0) file_type = edit->file_type;
  if (edit && !edit->dims.empty()) dims = edit->dims;
  values.resize(std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>()));
  if (edit && edit->nan_at) values.at(*edit->nan_at) = std::numeric_limits<T>::quiet_NaN();
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t ds = H5Dcreate2(file, key.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (ds < 0) throw std::runtime_error("raw HDF5 writer: cannot create " + key);
  check(H5Dwrite(ds, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write");
  H5Dclose(ds);
  H5Sclose(space);
}

void write_fixed_string_attribute(hid_t file, const std::string& name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  check(H5Tset_size(type, std::max<std::size_t>(value.size(), 1)), "string size");
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(file, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  check(H5Awrite(attr, type, value.c_str()), "attribute write");
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

std::vector<float> floats_of(const float* p, Eigen::Index n) { return {p, p + n}; }

}  // namespace

void write_raw_d4rl(const std::string& path, const Dataset& d, const std::vector<KeyEdit>& edits) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("raw HDF5 writer: cannot create " + path);
  const hsize_t n = d.size();
  const hsize_t obs = static_cast<hsize_t>(d.obs_dim()), act = static_cast<hsize_t>(d.act_dim());
  const auto float_key = [&](const char* key, const float* p, Eigen::Index count, std::vector<hsize_t> dims) {
    write_array(file, key, floats_of(p, count), std::move(dims), H5T_IEEE_F32LE, H5T_NATIVE_FLOAT,
                edit_for(edits, key));
  };
  float_key("observations", d.observations.data(), d.observations.size(), {n, obs});
  float_key("actions", d.actions.data(), d.actions.size(), {n, act});
  float_key("rewards", d.rewards.data(), d.rewards.size(), {n});
  float_key("next_observations", d.next_observations.data(), d.next_observations.size(), {n, obs});

  const hid_t bool_type = make_bool_enum();
  const auto flag_key = [&](const char* key, const std::vector<bool>& flags) {
    const KeyEdit* edit = edit_for(edits, key);
    // HDF5 converts int8 to other integers and floats but not to an enum: write the enum as itself.
    const bool as_enum = !edit || edit->file_type < 0;
    write_array(file, key, std::vector<std::int8_t>(flags.begin(), flags.end()), {n}, bool_type,
                as_enum ? bool_type : H5T_NATIVE_INT8, edit);
  };
  flag_key("terminals", d.terminals);
  flag_key("timeouts", d.timeouts);
  H5Tclose(bool_type);

  for (const auto& [name, value] : d.metadata) write_fixed_string_attribute(file, name, value);
  check(H5Fclose(file), "close");
}

}  // namespace rapid::testing
