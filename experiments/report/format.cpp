#include "experiments/report/format.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "algos/registry.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"

namespace rapid {

std::string fixed(double x, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  std::string s = buf;
  if (s.find_first_not_of("-0.") == std::string::npos && s.front() == '-') s.erase(0, 1);  // no "-0.0"
  return s;
}

std::string markdown_text(std::string text) {
  for (char& ch : text)
    if (ch == '\n' || ch == '\r' || ch == '|') ch = ' ';
  std::string out;
  for (const char ch : text) {
    if (ch == '<' || ch == '>' || ch == '*' || ch == '_' || ch == '`' || ch == '[' || ch == ']' || ch == '#' || ch == '\\')
      out += '\\';
    out += ch;
  }
  return out;
}

std::string share_text(double part, double whole, int decimals) {
  if (!(std::isfinite(part) && std::isfinite(whole)) || whole == 0.0) return "—";
  return fixed(100.0 * part / whole, decimals) + " %";
}

std::string short_number(std::optional<double> x) {
  if (!x || std::isnan(*x)) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", *x);
  return buf;
}

std::string run_cost_text(double median_s, double min_s, double max_s) {
  const auto seconds = [](double x) { return fixed(x, x < 10.0 ? 1 : 0); };
  return seconds(median_s) + " [" + seconds(min_s) + ", " + seconds(max_s) + "]";
}

std::string exact_number(std::optional<double> x) {
  if (!x || std::isnan(*x)) return "";
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, *x);
  return std::string(buf, result.ptr);
}

int table_decimals(double magnitude) {
  if (magnitude >= 100.0) return 1;
  if (magnitude >= 1.0) return 2;
  return 3;
}

std::string seed_count_note(int n_ok, int n_expected) {
  return "(n=" + std::to_string(n_ok) + "/" + std::to_string(n_expected) + ")";
}

std::string table_cell_text(std::optional<double> mean, std::optional<double> std, int n_ok, int n_expected,
                            int decimals, const std::string& pm, const std::string& dash) {
  if (!mean) return dash + " " + seed_count_note(n_ok, n_expected);
  std::string text = fixed(*mean, decimals) + pm + fixed(std.value_or(0.0), decimals);
  if (n_ok < n_expected) text += " " + seed_count_note(n_ok, n_expected);
  return text;
}

namespace {
std::string lookup(const std::map<std::string, std::string>& names, const std::string& key) {
  const auto it = names.find(key);
  return it == names.end() ? key : it->second;
}
}  // namespace

std::string algo_display_name(const std::string& algo) {
  const Algorithm* a = lookup_algorithm(algo);
  return a == nullptr ? algo : a->display_name;
}

std::string dataset_display_name(const std::string& dataset) {
  static const std::map<std::string, std::string> names = {
      {"initial", "Initial"}, {"medium", "Medium"}, {"final", "Final"}, {"final+medium", "Final+Medium"}};
  return lookup(names, dataset);
}

std::string scenario_display_name(const std::string& scenario) {
  if (scenario == "pendulum") return "Pendulum";
  if (!is_driving_scenario(scenario)) return scenario;
  try {
    return scenario_descriptor(scenario)->display_name;  // its descriptor says
  } catch (const std::invalid_argument&) {
    return scenario;  // a scenario file the report's machine does not have
  }
}

}  // namespace rapid
