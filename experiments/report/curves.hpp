// Curves of a cell averaged over its seeds: the evaluation return (Figure 2, claim C5) and the
// BC losses (Figure 3(b), claim C6).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "experiments/report/summary.hpp"

namespace rapid {

// Groups the points of records[*][array] by their x value and gives mean, std and count of the y
// values at each x, in increasing x. Points whose x or y is missing or null are skipped (prior BC
// loss without a prior buffer), so a curve may be empty. Evaluation curves align on
// "target_step": every seed evaluates at the same targets even if an episode overran one.
MeanCurve mean_curve(const std::vector<const nlohmann::json*>& records, const std::string& array,
                     const std::string& x_key, const std::string& y_key);

// An evaluation curve (of `y_key`: the return, or the collision rate): x is "target_step" where
// the records have it, else "step".
MeanCurve mean_eval_curve(const std::vector<const nlohmann::json*>& records, const std::string& y_key = "return_mean");

// One run's evaluations as (x, return_mean), x as mean_eval_curve aligns them.
std::vector<std::pair<double, double>> eval_points(const nlohmann::json& record);

// Trapezoid area under the mean curve divided by its step range (a step-weighted average return);
// nullopt with fewer than two points.
std::optional<double> normalized_area(const MeanCurve& curve);

// A record's BC-loss log as (step, prior, online), NaN for a null loss.
std::vector<std::tuple<double, double, double>> bc_loss_points(const nlohmann::json& record);

}  // namespace rapid
