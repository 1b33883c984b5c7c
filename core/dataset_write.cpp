// write_dataset: D4RL-layout HDF5, made in memory and written with write_file_atomic.
#include "core/atomic_file.hpp"
#include "core/dataset_hdf5_util.hpp"
#include "core/dataset_io.hpp"

namespace rapid {

namespace {

// The whole file, made in memory and taken as bytes (h5::file_image).
std::string hdf5_image(const Dataset& d) {
  H5::H5File file = h5::in_memory_file();
  const hsize_t n = d.size();
  h5::write_floats(file, h5::kObservations, d.observations.data(), n, d.obs_dim());
  h5::write_floats(file, h5::kActions, d.actions.data(), n, d.act_dim());
  h5::write_floats(file, h5::kRewards, d.rewards.data(), n, 0);
  h5::write_floats(file, h5::kNextObservations, d.next_observations.data(), n, d.obs_dim());
  h5::write_flags(file, h5::kTerminals, d.terminals);
  h5::write_flags(file, h5::kTimeouts, d.timeouts);
  for (const auto& [name, value] : d.metadata) h5::write_string_attribute(file, name, value);
  return h5::file_image(file);
}

void refuse_non_finite(const std::string& path, const char* key, std::optional<std::size_t> row) {
  if (row)
    throw DatasetError("refusing to write dataset " + path + ": '" + key + "' has a non-finite value at row " +
                       std::to_string(*row));
}

}  // namespace

void write_dataset(const std::string& path, const Dataset& dataset) {
  dataset.check_shapes();
  if (dataset.empty()) throw DatasetError("refusing to write dataset " + path + ": it holds no transitions");
  refuse_non_finite(path, h5::kObservations, h5::first_non_finite(dataset.observations));
  refuse_non_finite(path, h5::kActions, h5::first_non_finite(dataset.actions));
  refuse_non_finite(path, h5::kRewards, h5::first_non_finite(dataset.rewards));
  refuse_non_finite(path, h5::kNextObservations, h5::first_non_finite(dataset.next_observations));

  H5::Exception::dontPrint();  // errors become exceptions with our message, not stderr dumps
  std::string image;
  try {
    image = hdf5_image(dataset);
  } catch (const H5::Exception& e) {
    throw DatasetError("cannot write dataset " + path + ": " + h5::error_stack_detail(e.getDetailMsg()));
  }
  try {
    write_file_atomic(path, image);
  } catch (const FileWriteError& e) {
    throw DatasetError("cannot write dataset " + path + ": " + e.reason());
  }
}

}  // namespace rapid
