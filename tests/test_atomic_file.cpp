// Atomic writes and the clean-up of the temporaries a killed writer leaves behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/atomic_file.hpp"

using namespace rapid;
namespace fs = std::filesystem;

namespace {

class AtomicFile : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("rapid_atomic_test_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  std::string file(const std::string& name) const { return (dir / name).string(); }
  void touch(const std::string& name) const { std::ofstream(file(name)) << "x"; }
};

}  // namespace

TEST_F(AtomicFile, WritesWholeContentAndLeavesNoTemporary) {
  write_file_atomic(file("a.json"), "{\"k\": 1}");
  EXPECT_EQ(read_file(file("a.json")), "{\"k\": 1}");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(AtomicFile, RemovesOnlyTheTemporariesOfTheNamedFiles) {
  for (const char* f : {"record.json.tmp.4242", "initial.h5.tmp.77.3", "record.json", "initial.h5",
                        "notes.txt.tmp.12",           // a temporary of a file nobody named
                        "record.json.tmp.x",          // not a pid
                        "record.json.tmp.1.2.3",      // not one of the two writers' patterns
                        "record.json.tmpfile"})
    touch(f);
  EXPECT_EQ(remove_leftover_temporaries({file("record.json"), file("initial.h5"), file("missing.ckpt")}), 2);
  for (const char* gone : {"record.json.tmp.4242", "initial.h5.tmp.77.3"}) EXPECT_FALSE(fs::exists(file(gone))) << gone;
  for (const char* kept : {"record.json", "initial.h5", "notes.txt.tmp.12", "record.json.tmp.x", "record.json.tmp.1.2.3",
                           "record.json.tmpfile"})
    EXPECT_TRUE(fs::exists(file(kept))) << kept;
  // A folder that does not exist yet has nothing to clean.
  EXPECT_EQ(remove_leftover_temporaries({file("nowhere/record.json")}), 0);
}
