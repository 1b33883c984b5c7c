// `rapid sweep --reuse-datasets FROM`: a new sweep starts from another sweep's references and
// datasets when FROM built them for the same reference settings, copies them without touching
// FROM, leaves what it has alone, and builds itself what FROM built for other settings.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/dataset_io.hpp"
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

// A folder of a sweep's reference agents alone, as results/references/ holds them: the grid and
// each reference's agent folder (record and checkpoints) and job folder.
void copy_references(const fs::path& sweep, const fs::path& refs) {
  fs::create_directories(refs / "datasets/pendulum");
  fs::copy(sweep / "grid.json", refs / "grid.json");
  fs::copy(sweep / "datasets/pendulum/reference", refs / "datasets/pendulum/reference", fs::copy_options::recursive);
  fs::create_directories(refs / "jobs/pendulum");
  fs::copy(sweep / "jobs/pendulum/reference", refs / "jobs/pendulum/reference", fs::copy_options::recursive);
}

class ReuseDatasets : public ::testing::Test {
 protected:
  void SetUp() override {
    write_json(grid_path, pendulum_grid("reuse", {"rapid-rl", "ddpg"}, {0}, 600));
    provide_datasets(from, grid_path);
  }
  // `rapid sweep` of the grid into `sweep`, starting from `reuse`.
  Result sweep_reusing(const fs::path& reuse) {
    return run_rapid("sweep " + grid_path.string() + " --jobs 1 --no-summary --out " + sweep.string() +
                     " --reuse-datasets " + reuse.string());
  }
  // A real sweep of the grid (a trained reference and its datasets) into `built`, then a folder of
  // its reference agents alone.
  fs::path built_references() {
    EXPECT_EQ(run_rapid("sweep " + grid_path.string() + " --jobs 2 --no-summary --out " + built.string()).exit_code, 0);
    const fs::path refs = dir.path() / "refs";
    copy_references(built, refs);
    return refs;
  }
  testing::ScratchDir dir;
  const fs::path built = dir.path() / "built";
  const fs::path grid_path = dir.path() / "reuse.json", from = dir.path() / "from", sweep = dir.path() / "sweep";
};

TEST_F(ReuseDatasets, ASweepWithTheSameReferenceTrainsNoReferenceAndFromIsOnlyRead) {
  const std::string dataset = bytes_of(from / "datasets/pendulum/initial.h5");
  const Result r = sweep_reusing(from);
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

// A folder with the reference agents alone (results/references/: their records and checkpoints,
// not the datasets, which are too large to commit): the references are taken, the datasets
// collected here from them, identical to FROM's own; --check-references trains them instead and
// checks them against FROM's byte for byte.
TEST_F(ReuseDatasets, AFolderOfReferencesAloneGivesItsAgentsAndTheDatasetsAreCollectedHere) {
  const fs::path refs = built_references();
  const Dataset original = read_dataset((built / "datasets/pendulum/initial.h5").string());

  const Result r = sweep_reusing(refs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("reused the references and datasets of 0 of 1 scenario builds from " + refs.string() +
                          "; the references alone of 1 (their datasets are collected here)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(jobs_ran(sweep), (std::vector<std::string>{"pendulum/datasets", "pendulum/initial/rapid-rl/seed0",
                                                       "pendulum/none/ddpg/seed0"}));
  const Dataset collected = read_dataset((sweep / "datasets/pendulum/initial.h5").string());
  EXPECT_TRUE(collected.observations == original.observations && collected.actions == original.actions &&
              collected.rewards == original.rewards);
  EXPECT_EQ(collected.metadata.at("source_updates"), original.metadata.at("source_updates"));
  EXPECT_FALSE(fs::exists(refs / "datasets/pendulum/initial.h5")) << "FROM was written to";

  const fs::path checked = dir.path() / "checked";
  const std::string check = "sweep " + grid_path.string() + " --jobs 1 --no-summary --reuse-datasets " +
                            refs.string() + " --check-references --out ";
  const Result same = run_rapid(check + checked.string());
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("references: 1 trained here identical to " + refs.string() + ", 0 not"), std::string::npos)
      << same.output;
  EXPECT_EQ(jobs_ran(checked).front(), "pendulum/reference") << "the reference was trained, not copied";

  // A checkpoint that is not what this build trains is named, and the sweep fails.
  const fs::path ckpt = refs / "datasets/pendulum/reference/actor_60.ckpt";
  ASSERT_TRUE(fs::exists(ckpt));
  std::string bytes = bytes_of(ckpt);
  bytes[bytes.size() / 2] ^= 1;
  std::ofstream(ckpt, std::ios::binary | std::ios::trunc) << bytes;
  const Result differs = run_rapid(check + (dir.path() / "checked2").string());
  EXPECT_EQ(differs.exit_code, 1) << differs.output;
  EXPECT_NE(differs.output.find("pendulum/reference: actor_60.ckpt differs from " + ckpt.string()), std::string::npos)
      << differs.output;

  const Result alone = run_rapid("sweep " + grid_path.string() + " --check-references --out " + (dir.path() / "x").string());
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_NE(alone.output.find("--check-references: needs --reuse-datasets FROM"), std::string::npos) << alone.output;
}

// A reference whose record says ok but whose checkpoints are gone (a folder committed without its
// *.ckpt files) is not a reference: it is trained here, and `rapid status` says why in FROM.
TEST_F(ReuseDatasets, AReferenceWithoutItsCheckpointsIsTrainedHereNotTaken) {
  const fs::path refs = built_references();
  for (const auto& entry : fs::directory_iterator(refs / "datasets/pendulum/reference"))
    if (entry.path().extension() == ".ckpt") fs::remove(entry.path());

  const Result r = sweep_reusing(refs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("reused the references and datasets of 0 of 1 scenario builds from " + refs.string() +
                          "; 1 not done there for this grid's reference settings, built here"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(jobs_ran(sweep).front(), "pendulum/reference") << "the reference was trained, not copied";
  const Result status = run_rapid("status --json " + refs.string());
  EXPECT_NE(status.output.find("\"detail\": \"the reference checkpoint " + refs.string() +
                               "/datasets/pendulum/reference/actor_60.ckpt is missing, unreadable or holds an actor "
                               "without updates\""),
            std::string::npos)
      << status.output;
}

// The reference agents committed in results/references/flow are what the flow grids start from
// (README's main job): each one is done for their reference settings, checkpoints included, and
// every file is the one SHA256SUMS lists (a clone without the checkpoints fails here).
TEST(CommittedReferences, TheFlowGridsStartFromThemWithoutTraining) {
  const fs::path refs = fs::path(RAPID_SOURCE_DIR) / "results/references/flow";
  const std::string check = "cd '" + refs.string() + "' && sha256sum --quiet --check SHA256SUMS";
  EXPECT_EQ(std::system(check.c_str()), 0) << check;
  for (const char* grid : {"quick-flow.json", "paper-flow.json", "extension-flow.json"}) {
    const SweepFolder folder = make_sweep_folder(refs, load_grid(std::string(RAPID_SOURCE_DIR) + "/experiments/grids/" + grid));
    int references = 0;
    for (const SweepJob& job : folder.graph.jobs) {
      if (job.kind != JobKind::kReference) continue;
      ++references;
      EXPECT_TRUE(job_is_done(folder, job)) << grid << " " << job.id() << ": " << stage_job_problem(folder, job);
    }
    EXPECT_EQ(references, 3) << grid;
  }
}

// A scenario's references and datasets answer to its own reference settings: another scenario's
// L does not make them stale (quick-flow and paper-flow share theirs; so does a one-scenario grid).
TEST(DatasetStageInputs, AreTheScenariosOwnReferenceSettings) {
  nlohmann::json a = pendulum_grid("a", {"rapid-rl", "ddpg"}, {0}, 600);
  a["scenarios"] = {"pendulum", "merge"};
  a["reference"]["steps"] = {{"pendulum", 1200}, {"merge", 1200}};
  nlohmann::json b = a;
  b["reference"]["steps"]["merge"] = 2400;
  const SweepFolder fa = make_sweep_folder("/nonexistent/a", parse_grid(a, "a.json"));
  const SweepFolder fb = make_sweep_folder("/nonexistent/b", parse_grid(b, "b.json"));
  int compared = 0;
  for (const SweepJob& job : fa.graph.jobs) {
    if (job.kind == JobKind::kCell) continue;
    const bool same = dataset_stage_inputs_hash(fa, job) == dataset_stage_inputs_hash(fb, job);
    EXPECT_EQ(same, job.scenario == "pendulum") << job.id();
    ++compared;
  }
  EXPECT_EQ(compared, 4);  // a reference and a dataset job per scenario
}

TEST_F(ReuseDatasets, AFolderThatIsNotASweepIsRefusedInOneLine) {
  fs::create_directories(dir.path() / "plain");
  const Result r = sweep_reusing(dir.path() / "plain");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rapid: error: --reuse-datasets: '" + (dir.path() / "plain").string() +
                          "' is not a sweep folder (no grid.json)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(sweep)) << "refused before the sweep folder was made";
}

}  // namespace
}  // namespace rapid
