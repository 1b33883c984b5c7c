// Writing and reading D4RL-layout HDF5: exact round trips, h5py's types, and one clear error per
// kind of bad file.
#include <H5Cpp.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/dataset_io.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/datasets/raw_d4rl_writer.hpp"

namespace rapid {
namespace {

using testing::bit_identical;
using testing::KeyEdit;
using testing::make_dataset;
using testing::ScratchDir;
using testing::write_raw_d4rl;
using ::testing::HasSubstr;

// The message read_dataset throws for `path`, or "" if it reads fine.
std::string read_error(const std::string& path, const DatasetExpectation& expect = {}) {
  try {
    read_dataset(path, expect);
  } catch (const DatasetError& e) {
    return e.what();
  }
  return "";
}

TEST(DatasetIo, RoundTripIsBitExactWithMetadata) {
  ScratchDir dir;
  Dataset d = make_dataset(5, 2, {7, 3, 9, 4}, 42);
  d.metadata = {{meta::kScenario, "lane-drop"},       {meta::kSourceCheckpoint, "ckpt/final.bin"},
                {meta::kSeed, "90001"},               {meta::kConfigHash, "3f2a9c"},
                {meta::kCodeRevision, "abc123-dirty"}, {"note", "ünïcode ✓"}};
  write_dataset(dir.file("d.h5"), d);
  const Dataset back = read_dataset(dir.file("d.h5"), {5, 2, "lane-drop"});
  EXPECT_TRUE(bit_identical(d, back));
}

// The same data gives the same file bytes at any time: a prior cell's config hash covers its
// dataset file, so a rebuilt dataset must not make every cell look stale.
TEST(DatasetIo, SameDataGivesTheSameFileBytes) {
  ScratchDir dir;
  const Dataset d = make_dataset(5, 2, {7, 3}, 42);
  write_dataset(dir.file("a.h5"), d);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // HDF5 stamps times in seconds
  write_dataset(dir.file("b.h5"), d);
  EXPECT_EQ(read_file(dir.file("a.h5")), read_file(dir.file("b.h5")));
}

TEST(DatasetIo, RoundTripOfASingleTransition) {
  ScratchDir dir;
  const Dataset d = make_dataset(1, 1, {1}, 7);
  write_dataset(dir.file("one.h5"), d);
  EXPECT_TRUE(bit_identical(d, read_dataset(dir.file("one.h5"))));
}

TEST(DatasetIo, ReadsFilesOfOtherToolsContiguousWithFixedStrings) {
  ScratchDir dir;
  const Dataset d = make_dataset(3, 2, {4, 6}, 3);
  write_raw_d4rl(dir.file("raw.h5"), d);
  EXPECT_TRUE(bit_identical(d, read_dataset(dir.file("raw.h5"))));
}

TEST(DatasetIo, AcceptsByteFlagsAndColumnShapedRewards) {
  ScratchDir dir;
  const Dataset d = make_dataset(3, 2, {4, 6}, 3);
  const hsize_t n = d.size();
  write_raw_d4rl(dir.file("bytes.h5"), d,
                 {{.key = "terminals", .file_type = H5T_STD_U8LE}, {.key = "timeouts", .file_type = H5T_STD_I8LE},
                  {.key = "rewards", .dims = {n, 1}}});
  EXPECT_TRUE(bit_identical(d, read_dataset(dir.file("bytes.h5"))));
}

TEST(DatasetIo, StoresH5pyTypesWithChecksums) {
  ScratchDir dir;
  write_dataset(dir.file("d.h5"), make_dataset(4, 2, {5, 5}));
  H5::H5File file(dir.file("d.h5"), H5F_ACC_RDONLY);
  for (const char* key : {"observations", "actions", "rewards", "next_observations"}) {
    const H5::DataSet ds = file.openDataSet(key);
    EXPECT_TRUE(ds.getDataType() == H5::PredType::IEEE_F32LE) << key;
    const H5::DSetCreatPropList plist = ds.getCreatePlist();
    unsigned flags = 0, config = 0;
    std::size_t values = 0;
    EXPECT_EQ(H5Pget_filter2(plist.getId(), 0, &flags, &values, nullptr, 0, nullptr, &config), H5Z_FILTER_FLETCHER32)
        << key;
  }
  for (const char* key : {"terminals", "timeouts"}) {
    const H5::EnumType type = file.openDataSet(key).getEnumType();
    EXPECT_EQ(type.getNmembers(), 2) << key;
    EXPECT_EQ(type.getSize(), 1u) << key;
    EXPECT_TRUE(type.getSuper() == H5::PredType::STD_I8LE) << key;
    std::int8_t value = -1;
    type.valueOf("FALSE", &value);
    EXPECT_EQ(value, 0) << key;
    type.valueOf("TRUE", &value);
    EXPECT_EQ(value, 1) << key;
  }
  const H5::Attribute scenario = file.openGroup("/").openAttribute("scenario");
  EXPECT_TRUE(scenario.getStrType().isVariableStr());
}

TEST(DatasetIo, WrongActionDimensionNamesTheScenario) {
  ScratchDir dir;
  write_dataset(dir.file("d.h5"), make_dataset(6, 3, {5}));
  EXPECT_EQ(read_error(dir.file("d.h5"), {6, 2, "merge"}),
            "dataset " + dir.file("d.h5") + ": 'actions' has 3 columns, scenario merge expects 2");
}

TEST(DatasetIo, WrongObservationDimension) {
  ScratchDir dir;
  write_dataset(dir.file("d.h5"), make_dataset(6, 2, {5}));
  EXPECT_EQ(read_error(dir.file("d.h5"), {7, std::nullopt, ""}),
            "dataset " + dir.file("d.h5") + ": 'observations' has 6 columns, expected 7");
}

TEST(DatasetIo, MissingKey) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {5}), {{.key = "actions", .omit = true}});
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") + ": missing key 'actions'");
}

TEST(DatasetIo, SeveralMissingKeysAreAllNamed) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {5}),
                 {{.key = "rewards", .omit = true}, {.key = "timeouts", .omit = true}});
  EXPECT_THAT(read_error(dir.file("d.h5")), HasSubstr("missing keys 'rewards', 'timeouts'"));
}

TEST(DatasetIo, Float64ObservationsAreAWrongDtype) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {5}), {{.key = "observations", .file_type = H5T_IEEE_F64LE}});
  EXPECT_EQ(read_error(dir.file("d.h5")),
            "dataset " + dir.file("d.h5") + ": 'observations' is float64, expected float32");
}

TEST(DatasetIo, Int32ActionsAreAWrongDtype) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {5}), {{.key = "actions", .file_type = H5T_STD_I32LE}});
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") + ": 'actions' is int32, expected float32");
}

TEST(DatasetIo, FloatFlagsAreAWrongDtype) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {5}), {{.key = "terminals", .file_type = H5T_IEEE_F32LE}});
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") +
                                              ": 'terminals' is float32, expected bool (h5py's int8 enum) or an "
                                              "8-bit integer");
}

TEST(DatasetIo, RowCountsMustAgree) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {10}), {{.key = "rewards", .dims = {9}}});
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") + ": 'rewards' has 9 rows, 'observations' has 10");
}

TEST(DatasetIo, NextObservationWidthMustMatchObservations) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {10}), {{.key = "next_observations", .dims = {10, 4}}});
  EXPECT_EQ(read_error(dir.file("d.h5")),
            "dataset " + dir.file("d.h5") + ": 'next_observations' has 4 columns, 'observations' has 3");
}

TEST(DatasetIo, RanksAreChecked) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("a.h5"), make_dataset(3, 1, {10}), {{.key = "actions", .dims = {10}}});
  EXPECT_EQ(read_error(dir.file("a.h5")),
            "dataset " + dir.file("a.h5") + ": 'actions' has shape 10, expected 2-D (N × act_dim)");
  write_raw_d4rl(dir.file("r.h5"), make_dataset(3, 1, {10}), {{.key = "rewards", .dims = {10, 2}}});
  EXPECT_EQ(read_error(dir.file("r.h5")),
            "dataset " + dir.file("r.h5") + ": 'rewards' has shape 10 × 2, expected N or N × 1");
}

TEST(DatasetIo, EmptyFileIsAnError) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {}));
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") + ": holds no transitions");
}

TEST(DatasetIo, NonFiniteValuesAreRejected) {
  ScratchDir dir;
  write_raw_d4rl(dir.file("d.h5"), make_dataset(3, 2, {10}), {{.key = "rewards", .nan_at = 4}});
  EXPECT_EQ(read_error(dir.file("d.h5")),
            "dataset " + dir.file("d.h5") + ": 'rewards' has a non-finite value (NaN or inf) at row 4");
  // Element 7 of a row-major N × 3 array is in row 2.
  write_raw_d4rl(dir.file("o.h5"), make_dataset(3, 2, {10}), {{.key = "observations", .nan_at = 7}});
  EXPECT_THAT(read_error(dir.file("o.h5")), HasSubstr("'observations' has a non-finite value (NaN or inf) at row 2"));
}

TEST(DatasetIo, TruncatedFileIsAnErrorNotAShortDataset) {
  ScratchDir dir;
  write_dataset(dir.file("d.h5"), make_dataset(8, 2, {500, 500}));
  const auto full = std::filesystem::file_size(dir.file("d.h5"));
  std::filesystem::resize_file(dir.file("d.h5"), full / 2);
  const std::string message = read_error(dir.file("d.h5"));
  EXPECT_THAT(message, HasSubstr("dataset " + dir.file("d.h5") + ": unreadable HDF5 file (truncated file"));
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(DatasetIo, FlippedBitsFailTheChecksum) {
  ScratchDir dir;
  Dataset d = make_dataset(8, 2, {500, 500});
  const float marker = 1234.5678f;
  d.observations.setConstant(marker);
  write_dataset(dir.file("d.h5"), d);
  // Damage one stored observation in place.
  std::string bytes;
  {
    std::ifstream in(dir.file("d.h5"), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string pattern(reinterpret_cast<const char*>(&marker), sizeof marker);
  const auto at = bytes.find(pattern);
  ASSERT_NE(at, std::string::npos);
  bytes[at] ^= 0x01;
  std::ofstream(dir.file("d.h5"), std::ios::binary) << bytes;
  EXPECT_EQ(read_error(dir.file("d.h5")), "dataset " + dir.file("d.h5") +
                                              ": cannot read 'observations' (corrupt file?): data error detected by "
                                              "Fletcher32 checksum");
}

TEST(DatasetIo, MissingAndForeignFiles) {
  ScratchDir dir;
  EXPECT_EQ(read_error(dir.file("nope.h5")), "dataset " + dir.file("nope.h5") + ": no such file");
  std::ofstream(dir.file("text.h5")) << "not hdf5\n";
  EXPECT_EQ(read_error(dir.file("text.h5")), "dataset " + dir.file("text.h5") + ": not an HDF5 file");
  EXPECT_EQ(read_error(dir.path().string()), "dataset " + dir.path().string() + ": is a directory, not an HDF5 file");
}

TEST(DatasetIo, WriteRefusesWhatReadWouldReject) {
  ScratchDir dir;
  Dataset d = make_dataset(3, 2, {5});
  d.actions(1, 3) = std::numeric_limits<float>::infinity();
  EXPECT_THROW(write_dataset(dir.file("inf.h5"), d), DatasetError);
  EXPECT_THROW(write_dataset(dir.file("empty.h5"), make_dataset(3, 2, {})), DatasetError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("inf.h5")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("empty.h5")));
}

TEST(DatasetIo, WriteReplacesAtomicallyAndLeavesNoTemporaries) {
  ScratchDir dir;
  write_dataset(dir.file("d.h5"), make_dataset(3, 2, {5}, 1));
  const Dataset second = make_dataset(3, 2, {8, 2}, 2);
  write_dataset(dir.file("d.h5"), second);
  EXPECT_TRUE(bit_identical(second, read_dataset(dir.file("d.h5"))));
  const auto entries = std::distance(std::filesystem::directory_iterator(dir.path()), {});
  EXPECT_EQ(entries, 1);
}

// docs/design.md §Sweeps: a writer killed at any moment leaves the old file or the new one, never a part.
TEST(DatasetIo, KilledWriterNeverLeavesAPartialFile) {
  ScratchDir dir;
  const std::string target = dir.file("d.h5");
  const Dataset old_data = make_dataset(16, 2, {100}, 1);
  const Dataset new_data = make_dataset(16, 2, {20000, 20000}, 2);  // a few MB: takes a while
  write_dataset(target, old_data);
  for (int delay_ms : {1, 5, 20, 60}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      for (;;) write_dataset(target, new_data);  // until killed
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    const Dataset back = read_dataset(target);  // throws if the target is a partial file
    EXPECT_TRUE(bit_identical(back, back.size() == old_data.size() ? old_data : new_data)) << delay_ms << " ms";
  }
}

TEST(DatasetIo, FailedWriteNamesThePathAndLeavesNothing) {
  ScratchDir dir;
  const std::string target = dir.file("no/such/dir/d.h5");
  try {
    write_dataset(target, make_dataset(3, 2, {5}));
    FAIL() << "expected a DatasetError";
  } catch (const DatasetError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("cannot write dataset " + target + ": "));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0);
}

}  // namespace
}  // namespace rapid
