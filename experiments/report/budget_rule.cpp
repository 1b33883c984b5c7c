#include "experiments/report/budget_rule.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace rapid {

namespace {
double mean_over(const std::vector<long>& steps, const std::vector<double>& c, double from, double to) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (steps[i] >= from && steps[i] < to) sum += c[i], ++n;
  if (n == 0) throw std::invalid_argument("the curves have no evaluation between steps " + std::to_string(long(from)) +
                                          " and " + std::to_string(long(to)));
  return sum / n;
}
}  // namespace

BudgetRuleResult apply_budget_rule(const std::vector<ReferenceCurve>& curves, const BudgetRuleOptions& o) {
  if (curves.empty()) throw std::invalid_argument("no reference curves");
  const std::vector<long>& steps = curves.front().steps;
  if (steps.size() < 4 || steps.front() != 0)
    throw std::invalid_argument(curves.front().label + ": the curve must start at step 0 and have at least 4 evaluations");
  for (const auto& c : curves) {
    if (c.steps != steps) throw std::invalid_argument(c.label + ": its evaluation steps differ from " + curves.front().label + "'s");
    if (c.returns.size() != steps.size()) throw std::invalid_argument(c.label + ": steps and returns differ in length");
  }
  BudgetRuleResult r;
  r.steps = steps;
  r.long_run = steps.back();
  const std::size_t n = steps.size();
  r.mean.assign(n, 0.0);
  for (const auto& c : curves)
    for (std::size_t i = 0; i < n; ++i) r.mean[i] += c.returns[i] / static_cast<double>(curves.size());
  r.smoothed.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t from = i + 1 >= static_cast<std::size_t>(o.smoothing) ? i + 1 - o.smoothing : 0;
    double sum = 0.0;
    for (std::size_t k = from; k <= i; ++k) sum += r.mean[k];
    r.smoothed[i] = sum / static_cast<double>(i - from + 1);
  }
  const double L = static_cast<double>(r.long_run);
  r.r0 = r.mean.front();
  r.plateau = mean_over(steps, r.mean, 0.75 * L, L + 1.0);
  r.third_quarter = mean_over(steps, r.mean, 0.5 * L, 0.75 * L);
  const double gap = r.plateau - r.r0;
  if (!(gap > 0.0))
    throw std::invalid_argument("the reference's plateau (" + std::to_string(r.plateau) +
                                ") is not above its untrained return (" + std::to_string(r.r0) + "): it did not learn");
  r.plateau_band = o.plateau_tolerance * gap;
  r.plateaued = std::abs(r.third_quarter - r.plateau) <= r.plateau_band;
  r.fraction = o.fraction;
  r.threshold = r.r0 + o.fraction * gap;
  for (std::size_t i = 0; i < n; ++i)
    if (r.smoothed[i] >= r.threshold) {
      r.budget = steps[i];
      break;
    }
  return r;
}

namespace {
namespace fs = std::filesystem;

// One record's curve; false when it is not an ok DDPG run.
bool read_curve(const fs::path& path, std::string& scenario, ReferenceCurve& curve) {
  std::ifstream in(path);
  nlohmann::json r;
  try {
    r = nlohmann::json::parse(in);
    if (r.value("status", "") != "ok" || r.at("cell").value("algo", "") != "ddpg") return false;
    scenario = r.at("cell").at("scenario").get<std::string>();
    for (const auto& e : r.at("eval")) {
      curve.steps.push_back(e.contains("target_step") ? e.at("target_step").get<long>() : e.at("step").get<long>());
      curve.returns.push_back(e.at("return_mean").get<double>());
    }
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument("record " + path.string() + " cannot be read: " + e.what());
  }
  return true;
}
}  // namespace

std::map<std::string, std::vector<ReferenceCurve>> read_reference_curves(const std::string& dir) {
  if (!fs::is_directory(dir)) throw std::invalid_argument("'" + dir + "' is not a folder");
  std::vector<fs::path> records;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() == "record.json") records.push_back(entry.path());
  std::sort(records.begin(), records.end());  // a stable order: the mean does not depend on the file system's
  std::map<std::string, std::vector<ReferenceCurve>> curves;
  for (const fs::path& path : records) {
    std::string scenario;
    ReferenceCurve curve;
    curve.label = fs::relative(path.parent_path(), dir).string();
    if (read_curve(path, scenario, curve)) curves[scenario].push_back(std::move(curve));
  }
  if (curves.empty()) throw std::invalid_argument("'" + dir + "' holds no ok DDPG record.json");
  return curves;
}

std::string budget_rule_report(const std::string& scenario, const std::vector<ReferenceCurve>& curves,
                               const BudgetRuleResult& r) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << scenario << ": " << curves.size() << " reference run(s), L = " << r.long_run << ", E = "
      << (r.steps.size() > 1 ? r.steps[1] - r.steps[0] : 0) << "\n";
  out << "  R0 = " << r.r0 << "  P = " << r.plateau << "  third quarter = " << r.third_quarter << "\n";
  out << "  plateau check: |" << r.third_quarter << " - " << r.plateau << "| "
      << (r.plateaued ? "<= " : "> ") << r.plateau_band << (r.plateaued ? "  passed" : "  FAILED") << "\n";
  if (!r.plateaued) {
    out << "  the reference has not plateaued: train it for L = " << 2 * r.long_run << " and apply the rule again\n";
    return out.str();
  }
  out << "  threshold R0 + " << r.fraction << " (P - R0) = " << r.threshold << "\n";
  if (r.budget < 0) {
    out << "  s(t) never reaches the threshold: no budget\n";
    return out.str();
  }
  out << "  T = " << r.budget << "  (initial at T/10 = " << r.budget / 10 << ", medium at T/2 = " << r.budget / 2
      << ", final at L = " << r.long_run << ")\n";
  return out.str();
}

}  // namespace rapid
