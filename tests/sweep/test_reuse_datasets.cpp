// `rapid sweep --reuse-datasets FROM`: a new sweep starts from another sweep's references and
// datasets when FROM built them for the same reference settings, copies them without touching
// FROM, leaves what it has alone, and builds itself what FROM built for other settings.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "experiments/sweep/reuse_datasets.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class ReuseDatasets : public ::testing::Test {
 protected:
  void SetUp() override {
    write_json(grid_path, pendulum_grid("reuse", {"rapid-rl", "ddpg"}, {0}, 600));
    provide_datasets(from, grid_path);
  }
  testing::ScratchDir dir;
  const fs::path grid_path = dir.path() / "reuse.json", from = dir.path() / "from", sweep = dir.path() / "sweep";
};

TEST_F(ReuseDatasets, ASweepWithTheSameReferenceTrainsNoReferenceAndFromIsOnlyRead) {
  const std::string dataset = bytes_of(from / "datasets/pendulum/initial.h5");
  const Result r = run_rapid("sweep " + grid_path.string() + " --jobs 1 --no-summary --out " + sweep.string() +
                             " --reuse-datasets " + from.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("reused the references and datasets of 1 of 1 scenario builds from " + from.string()),
            std::string::npos)
      << r.output;
  // Only the two cells ran: the reference and dataset jobs were done, as copied.
  EXPECT_EQ(jobs_ran(sweep), (std::vector<std::string>{"pendulum/initial/rapid-rl/seed0", "pendulum/none/ddpg/seed0"}));
  EXPECT_EQ(bytes_of(sweep / "datasets/pendulum/initial.h5"), dataset);
  EXPECT_EQ(bytes_of(from / "datasets/pendulum/initial.h5"), dataset);
  EXPECT_FALSE(fs::exists(from / "jobs/pendulum/initial")) << "FROM gained cells";

  // Asked again, it finds its own copy and leaves it alone.
  const ReuseReport again = reuse_datasets(open_sweep_folder(sweep), open_sweep_folder(from));
  EXPECT_TRUE(again.copied.empty());
  EXPECT_EQ(again.present, (std::vector<std::string>{"pendulum/datasets"}));
}

TEST_F(ReuseDatasets, DatasetsBuiltForOtherReferenceSettingsAreNotTaken) {
  nlohmann::json other = pendulum_grid("reuse", {"rapid-rl", "ddpg"}, {0}, 600);
  other["reference"]["seed"] = 1001;
  const ReuseReport r = reuse_datasets(make_sweep_folder(sweep, parse_grid(other, "other.json")), open_sweep_folder(from));
  EXPECT_TRUE(r.copied.empty());
  EXPECT_EQ(r.stale, (std::vector<std::string>{"pendulum/datasets"}));
  EXPECT_FALSE(fs::exists(sweep / "datasets"));
}

TEST_F(ReuseDatasets, AFolderThatIsNotASweepIsRefusedInOneLine) {
  fs::create_directories(dir.path() / "plain");
  const Result r = run_rapid("sweep " + grid_path.string() + " --jobs 1 --no-summary --out " + sweep.string() +
                             " --reuse-datasets " + (dir.path() / "plain").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rapid: error: --reuse-datasets: '" + (dir.path() / "plain").string() +
                          "' is not a sweep folder (no grid.json)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(sweep)) << "refused before the sweep folder was made";
}

}  // namespace
}  // namespace rapid
