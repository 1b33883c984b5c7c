// `rapid recheck SWEEP --seeds A-B`: the grid again on new seeds, from the sweep's references and
// datasets (none retrained), and recheck.md with each claim's verdict beside the original's.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/sweep/sweep_test_util.hpp"

namespace rapid {
namespace {

using namespace sweep_test;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Recheck, RerunsTheCellsOnNewSeedsFromTheSweepsDatasetsAndComparesTheVerdicts) {
  testing::ScratchDir dir;
  const fs::path grid = dir.path() / "g.json", sweep = dir.path() / "sweep";
  write_json(grid, pendulum_grid("g", {"rapid-rl", "ddpg"}, {0, 1}, 400));
  ASSERT_EQ(run_rapid("sweep " + grid.string() + " --jobs 2 --no-summary --out " + sweep.string()).exit_code, 0);

  const Result r = run_rapid("recheck " + sweep.string() + " --seeds 100-101 --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path recheck = dir.path() / "sweep-recheck";
  EXPECT_EQ(jobs_ran(recheck), (std::vector<std::string>{"pendulum/initial/rapid-rl/seed100",
                                                        "pendulum/initial/rapid-rl/seed101", "pendulum/none/ddpg/seed100",
                                                        "pendulum/none/ddpg/seed101"}));
  EXPECT_EQ(read_json(recheck / "grid.json")["seeds"], nlohmann::json({100, 101}));
  const std::string md = read_text(recheck / "recheck.md");
  EXPECT_NE(md.find("(original: 0, 1; recheck: 100, 101)"), std::string::npos) << md;
  EXPECT_NE(md.find("| C2 | "), std::string::npos) << md;
  EXPECT_NE(r.output.find("# Recheck of `g`"), std::string::npos) << r.output;

  // Seeds the sweep used, or no sweep at all: exit 2, one line, nothing made.
  const Result own = run_rapid("recheck " + sweep.string() + " --seeds 1-3 --out " + (dir.path() / "x").string());
  EXPECT_EQ(own.exit_code, 2);
  EXPECT_EQ(own.output, "rapid: error: --seeds: seed 1 is one of the sweep's own seeds; a recheck needs new ones\n");
  EXPECT_FALSE(fs::exists(dir.path() / "x"));
  const Result none = run_rapid("recheck " + (dir.path() / "nothing").string() + " --seeds 5-6");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.output.find("SWEEP_DIR: "), std::string::npos) << none.output;

  // --out at another grid's sweep folder (here the original itself) is refused, not rewritten.
  const nlohmann::json before = read_json(sweep / "grid.json");
  const Result other = run_rapid("recheck " + sweep.string() + " --seeds 200-201 --out " + sweep.string());
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.output.find("is the sweep folder of grid \"g\", not this recheck's ('g-recheck')"), std::string::npos)
      << other.output;
  EXPECT_EQ(read_json(sweep / "grid.json"), before);
  EXPECT_FALSE(fs::exists(sweep / "jobs/pendulum/none/ddpg/seed200"));
  // The recheck's own folder resumes: nothing new to run.
  const Result again = run_rapid("recheck " + sweep.string() + " --seeds 100-101 --jobs 2");
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

}  // namespace
}  // namespace rapid
