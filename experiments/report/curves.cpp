#include "experiments/report/curves.hpp"

#include <limits>

#include <map>

#include "core/statistics.hpp"
#include "experiments/run/json_numbers.hpp"

namespace rapid {

MeanCurve mean_curve(const std::vector<const nlohmann::json*>& records, const std::string& array,
                     const std::string& x_key, const std::string& y_key) {
  std::map<double, std::vector<double>> by_x;
  for (const nlohmann::json* record : records) {
    if (!record->contains(array) || !(*record)[array].is_array()) continue;
    for (const nlohmann::json& point : (*record)[array]) {
      if (!point.is_object() || !point.contains(x_key) || !point.contains(y_key)) continue;
      const nlohmann::json &x = point[x_key], &y = point[y_key];
      if (!x.is_number() || !y.is_number()) continue;
      by_x[x.get<double>()].push_back(y.get<double>());
    }
  }
  MeanCurve curve;
  for (const auto& [x, ys] : by_x) {
    curve.step.push_back(x);
    curve.mean.push_back(mean(ys));
    curve.std.push_back(population_std(ys));
    curve.n.push_back(static_cast<int>(ys.size()));
  }
  return curve;
}

MeanCurve mean_eval_curve(const std::vector<const nlohmann::json*>& records, const std::string& y_key) {
  bool has_target = !records.empty();
  for (const nlohmann::json* record : records) {
    const auto& eval = record->contains("eval") ? (*record)["eval"] : nlohmann::json();
    if (eval.is_array() && !eval.empty() && !eval.front().contains("target_step")) has_target = false;
  }
  return mean_curve(records, "eval", has_target ? "target_step" : "step", y_key);
}

std::vector<std::pair<double, double>> eval_points(const nlohmann::json& record) {
  std::vector<std::pair<double, double>> out;
  if (!record.contains("eval") || !record["eval"].is_array()) return out;
  for (const nlohmann::json& point : record["eval"]) {
    if (!point.is_object()) continue;
    const char* x_key = point.contains("target_step") ? "target_step" : "step";
    if (!point.contains(x_key) || !point.contains("return_mean")) continue;
    const nlohmann::json &x = point[x_key], &y = point["return_mean"];
    if (x.is_number() && y.is_number()) out.emplace_back(x.get<double>(), y.get<double>());
  }
  return out;
}

std::vector<std::tuple<double, double, double>> bc_loss_points(const nlohmann::json& record) {
  std::vector<std::tuple<double, double, double>> out;
  if (!record.contains("bc_loss") || !record["bc_loss"].is_array()) return out;
  const auto number = [](const nlohmann::json& p, const char* key) {
    return optional_number(p, key).value_or(std::numeric_limits<double>::quiet_NaN());  // a null loss: NaN
  };
  for (const nlohmann::json& point : record["bc_loss"])
    if (point.is_object() && point.contains("step") && point["step"].is_number())
      out.emplace_back(point["step"].get<double>(), number(point, "prior"), number(point, "online"));
  return out;
}

std::optional<double> normalized_area(const MeanCurve& curve) {
  if (curve.step.size() < 2) return std::nullopt;
  const double range = curve.step.back() - curve.step.front();
  if (!(range > 0)) return std::nullopt;
  double area = 0.0;
  for (std::size_t i = 1; i < curve.step.size(); ++i)
    area += (curve.step[i] - curve.step[i - 1]) * (curve.mean[i] + curve.mean[i - 1]) / 2.0;
  return area / range;
}

}  // namespace rapid
