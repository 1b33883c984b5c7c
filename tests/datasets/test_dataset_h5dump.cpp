// The file layout as HDF5's own tool sees it: what Python D4RL tooling will find.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/dataset_io.hpp"
#include "tests/datasets/dataset_fixtures.hpp"

namespace rapid {
namespace {

using ::testing::HasSubstr;

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, n);
  ::pclose(pipe);
  return out;
}

// The header lines h5dump prints for one dataset: from its DATASET line to the next one.
std::string block_of(const std::string& dump, const std::string& key) {
  const auto begin = dump.find("DATASET \"" + key + "\"");
  if (begin == std::string::npos) return "";
  return dump.substr(begin, dump.find("DATASET \"", begin + 1) - begin);
}

// Collapses runs of whitespace, so the checks do not depend on h5dump's column alignment.
std::string squeezed(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool space = c == ' ' || c == '\n' || c == '\t';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out += space ? ' ' : c;
  }
  return out;
}

TEST(DatasetH5dump, ListsTheD4rlKeysWithTheirTypes) {
  if (std::system("command -v h5dump > /dev/null 2>&1") != 0) GTEST_SKIP() << "h5dump is not on PATH";
  testing::ScratchDir dir;
  write_dataset(dir.file("d.h5"), testing::make_dataset(4, 2, {6, 4}));
  const std::string dump = run("h5dump -H " + dir.file("d.h5"));
  ASSERT_THAT(dump, HasSubstr("HDF5 \"" + dir.file("d.h5") + "\""));

  const std::pair<const char*, const char*> float_keys[] = {
      {"observations", "( 10, 4 )"}, {"actions", "( 10, 2 )"}, {"rewards", "( 10 )"}, {"next_observations", "( 10, 4 )"}};
  for (const auto& [key, shape] : float_keys) {
    const std::string block = squeezed(block_of(dump, key));
    EXPECT_THAT(block, HasSubstr("DATATYPE H5T_IEEE_F32LE")) << key;
    EXPECT_THAT(block, HasSubstr(std::string("DATASPACE SIMPLE { ") + shape)) << key;
  }
  for (const char* key : {"terminals", "timeouts"}) {
    const std::string block = squeezed(block_of(dump, key));
    EXPECT_THAT(block, HasSubstr("DATATYPE H5T_ENUM { H5T_STD_I8LE; \"FALSE\" 0; \"TRUE\" 1; }")) << key;
    EXPECT_THAT(block, HasSubstr("DATASPACE SIMPLE { ( 10 )")) << key;
  }
  EXPECT_THAT(squeezed(dump), HasSubstr("ATTRIBUTE \"scenario\" { DATATYPE H5T_STRING { STRSIZE H5T_VARIABLE;"));
}

}  // namespace
}  // namespace rapid
