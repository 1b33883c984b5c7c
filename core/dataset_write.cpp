// write_dataset: D4RL-layout HDF5, written to a temporary file and renamed into place.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/dataset_hdf5_util.hpp"
#include "core/dataset_io.hpp"

namespace rapid {

namespace {

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

// `rows` × `cols` floats from a column-major cols × rows matrix (the same bytes, row-major);
// cols == 0 writes a 1-D array of `rows` values.
void write_floats(H5::H5File& file, const char* key, const float* data, hsize_t rows, hsize_t cols) {
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {rows, cols};
  H5::DataSpace space(rank, dims);
  H5::DataSet ds = file.createDataSet(key, H5::PredType::IEEE_F32LE, space, checksummed_chunks(rank, dims, 4));
  ds.write(data, H5::PredType::NATIVE_FLOAT);
}

void write_flags(H5::H5File& file, const char* key, const std::vector<bool>& flags) {
  const std::vector<std::int8_t> bytes(flags.begin(), flags.end());
  const hsize_t dims[1] = {bytes.size()};
  H5::DataSpace space(1, dims);
  const H5::EnumType type = h5::bool_enum_type();
  H5::DataSet ds = file.createDataSet(key, type, space, checksummed_chunks(1, dims, 1));
  ds.write(bytes.data(), type);
}

// Variable-length UTF-8, what h5py writes for a Python str, so it reads back as str.
void write_string_attribute(H5::H5File& file, const std::string& name, const std::string& value) {
  H5::StrType type(H5::PredType::C_S1, H5T_VARIABLE);
  type.setCset(H5T_CSET_UTF8);
  H5::Attribute attr = file.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attr.write(type, value);
}

void write_hdf5(const std::string& file_path, const Dataset& d) {
  H5::H5File file(file_path, H5F_ACC_TRUNC);
  const hsize_t n = d.size();
  write_floats(file, h5::kObservations, d.observations.data(), n, d.obs_dim());
  write_floats(file, h5::kActions, d.actions.data(), n, d.act_dim());
  write_floats(file, h5::kRewards, d.rewards.data(), n, 0);
  write_floats(file, h5::kNextObservations, d.next_observations.data(), n, d.obs_dim());
  write_flags(file, h5::kTerminals, d.terminals);
  write_flags(file, h5::kTimeouts, d.timeouts);
  for (const auto& [name, value] : d.metadata) write_string_attribute(file, name, value);
  file.close();
}

// Unique per process and per call, in the target's directory so the rename stays on one
// filesystem (and is therefore atomic).
std::string temporary_path_beside(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

// HDF5 closes the file without fsync; without it a crash after the rename could leave the target
// name pointing at unwritten blocks.
void flush_to_disk(const std::string& file_path) {
  const int fd = ::open(file_path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw DatasetError(std::strerror(errno));
  const bool synced = ::fsync(fd) == 0;
  const int sync_errno = errno;
  ::close(fd);
  if (!synced) throw DatasetError(std::strerror(sync_errno));
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
  const std::string tmp = temporary_path_beside(path);
  try {
    write_hdf5(tmp, dataset);
    flush_to_disk(tmp);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) throw DatasetError(std::strerror(errno));
  } catch (const H5::Exception& e) {
    std::remove(tmp.c_str());
    throw DatasetError("cannot write dataset " + path + ": " + h5::error_stack_detail(e.getDetailMsg()));
  } catch (const DatasetError& e) {
    std::remove(tmp.c_str());
    throw DatasetError("cannot write dataset " + path + ": " + e.what());
  }
}

}  // namespace rapid
