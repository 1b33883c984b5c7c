// The hand-made merge sweep the decided-claims tests share (short profile: δ = 11.8).
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/report/summarize.hpp"
#include "tests/datasets/dataset_fixtures.hpp"
#include "tests/reports/report_test_util.hpp"

namespace rapid {

using report_test::FakeRun;

const std::vector<std::string> kAlgos = {"rapid-rl", "rlpd", "col-prior", "col-all", "ddpg"};
const std::vector<std::string> kDatasets = {"initial", "final+medium"};

// A merge sweep (short profile: δ = 11.8) of `seeds` seeds whose final returns are
// mean(dataset, algo) + the seed's offset, offsets spread symmetrically with the given std.
class DecisionsTest : public ::testing::Test {
 protected:
  testing::ScratchDir scratch;
  std::filesystem::path sweep = scratch.path() / "sweep";

  Summary make(const std::function<double(const std::string& dataset, const std::string& algo)>& mean, int seeds,
               double spread, const std::vector<std::string>& algos = kAlgos,
               const nlohmann::json& claims = nullptr) {
    std::vector<int> seed_list;
    for (int i = 0; i < seeds; ++i) seed_list.push_back(i);
    nlohmann::json grid = report_test::make_grid("decide", {"merge"}, kDatasets, algos, seed_list);
    if (!claims.is_null()) grid["claims"] = claims;  // the grid's own, beside the paper's
    report_test::write_grid(sweep, grid);
    for (const std::string& algo : algos)
      for (const std::string& dataset : kDatasets) {
        if (algo == "ddpg" && dataset != kDatasets.front()) continue;
        for (int i = 0; i < seeds; ++i) {
          FakeRun r = report_test::pendulum_run(algo == "ddpg" ? "" : dataset, algo, static_cast<std::uint64_t>(i), 0.0);
          r.scenario = "merge";
          // Offsets −1, +1, −1, … scaled to the spread (population std exactly `spread` for even n).
          r.final_return = mean(algo == "ddpg" ? "" : dataset, algo) + (i % 2 == 0 ? -spread : spread);
          r.eval = {{0, 0.0}, {500, r.final_return / 2}, {1000, r.final_return}};
          report_test::write_run(sweep, r);
        }
      }
    return build_summary(sweep);
  }

  static const DecidedClaim& claim(const Summary& s, const std::string& id) {
    for (const DecidedClaim& c : s.decisions->claims)
      if (c.id == id) return c;
    throw std::runtime_error("no claim " + id);
  }
};

}  // namespace rapid
