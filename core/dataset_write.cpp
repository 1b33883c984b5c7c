// write_dataset: D4RL-layout HDF5, made in memory and written with write_file_atomic.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/atomic_file.hpp"
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

// How much the in-memory file grows at a time.
constexpr std::size_t kImageIncrement = 1 << 20;

// The whole HDF5 file, made in memory (the core driver without a backing store): HDF5 never
// writes to disk, so a full disk is one failed write() in write_file_atomic rather than an error
// inside HDF5, whose clean-up after a close that could not flush crashes (HDF5 1.10: H5Fclose
// after a failed H5Dclose, SIGSEGV). The bytes are those HDF5 writes to a file itself.
std::string hdf5_image(const Dataset& d) {
  H5::FileAccPropList in_memory;
  H5Pset_fapl_core(in_memory.getId(), kImageIncrement, /*backing_store=*/false);
  // HDF5 first tries to open the name as an existing file; under /dev/null none can exist, so
  // nothing on disk is touched.
  H5::H5File file("/dev/null/rapid-in-memory.h5", H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, in_memory);
  const hsize_t n = d.size();
  write_floats(file, h5::kObservations, d.observations.data(), n, d.obs_dim());
  write_floats(file, h5::kActions, d.actions.data(), n, d.act_dim());
  write_floats(file, h5::kRewards, d.rewards.data(), n, 0);
  write_floats(file, h5::kNextObservations, d.next_observations.data(), n, d.obs_dim());
  write_flags(file, h5::kTerminals, d.terminals);
  write_flags(file, h5::kTimeouts, d.timeouts);
  for (const auto& [name, value] : d.metadata) write_string_attribute(file, name, value);
  file.flush(H5F_SCOPE_GLOBAL);
  const ssize_t size = H5Fget_file_image(file.getId(), nullptr, 0);
  std::string image(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
  if (size <= 0 || H5Fget_file_image(file.getId(), image.data(), image.size()) != size)
    throw H5::FileIException("H5Fget_file_image", "cannot take the file's image");
  file.close();
  return image;
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
