// Atomic writes and the clean-up of the temporaries a killed writer leaves behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/atomic_file.hpp"
#include "tests/special_files.hpp"

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

// Replacing a file removes the old one: never what is not a regular file (a symlink, which the
// user's file behind it would lose, a FIFO, a device node, a folder).
TEST_F(AtomicFile, NeverReplacesWhatIsNotARegularFile) {
  touch("mine");
  fs::create_symlink(file("mine"), file("link"));
  ASSERT_TRUE(test::make_fifo(file("fifo")));
  fs::create_directories(file("folder"));
  std::vector<std::string> targets = {"link", "fifo", "folder"};
  const bool device = test::make_device(file("null"));  // root only
  if (device) targets.push_back("null");
  for (const std::string& name : targets) {
    try {
      write_file_atomic(file(name), "new");
      ADD_FAILURE() << name << " was replaced";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot write " + file(name)), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_symlink(file("link")));
  EXPECT_EQ(read_file(file("mine")), "x");
  EXPECT_TRUE(test::is_fifo(file("fifo")));
  EXPECT_TRUE(fs::is_directory(file("folder")));
  if (device) {
    EXPECT_TRUE(test::is_device(file("null")));
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 4 + device) << "no temporary left";
}

// The temporary's name is predictable ("<path>.tmp.<pid>"), so whatever another user planted
// there must not be written through (issue 46: a symlink there made `rapid diff --write-baseline`
// overwrite its target and leave the baseline a symlink to it). The writer creates its temporary
// exclusively, takes the next name when one is taken, and the target ends a regular file.
TEST_F(AtomicFile, NeverWritesThroughWhatIsPlantedAtItsTemporarysName) {
  std::ofstream(file("victim")) << "precious";
  const std::string stem = file("b.json") + ".tmp." + std::to_string(::getpid());
  fs::create_symlink(file("victim"), stem);
  fs::create_symlink(file("victim"), stem + ".1");
  write_file_atomic(file("b.json"), "baseline");
  EXPECT_EQ(read_file(file("victim")), "precious");
  EXPECT_FALSE(fs::is_symlink(file("b.json")));
  EXPECT_EQ(read_file(file("b.json")), "baseline");
  EXPECT_TRUE(fs::is_symlink(stem)) << "what was planted is not ours to remove";
  EXPECT_FALSE(fs::exists(stem + ".2")) << "the temporary was renamed into place";
}

// Reading a whole file is bounded and never blocks (issue 46: a 5 GB sparse network file was read
// whole into memory; a FIFO blocked forever): each is refused with a message naming the path.
TEST_F(AtomicFile, ReadingRefusesHugeFilesAndWhatIsNotARegularFile) {
  { std::ofstream(file("sparse")); }
  fs::resize_file(file("sparse"), kMaxReadBytes + 1);  // sparse: no disk used
  ASSERT_TRUE(test::make_fifo(file("fifo")));
  const auto message = [](const std::string& path) {
    try {
      read_file(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_EQ(message(file("sparse")), "cannot read " + file("sparse") + ": it is larger than 1024 MiB");
  EXPECT_EQ(message(file("fifo")), "cannot read " + file("fifo") + ": it is a FIFO, not a regular file");
  EXPECT_EQ(message(dir.string()), "cannot read " + dir.string() + ": it is a folder, not a regular file");
  std::ofstream(file("small")) << "abc";
  fs::create_symlink(file("small"), file("link"));
  EXPECT_EQ(read_file(file("link")), "abc") << "a symlink to a regular file is read";
}
