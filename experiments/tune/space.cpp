#include "experiments/tune/space.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <set>
#include <stdexcept>

#include "algos/registry.hpp"
#include "core/hash.hpp"
#include "core/json_input.hpp"
#include "core/printable.hpp"
#include "core/rng.hpp"
#include "experiments/run/config_keys.hpp"

namespace rapid {

namespace {

using nlohmann::json;

// Seeds from 100 up are kept for independent rechecks (the developers' guide), so tuning never uses them.
constexpr std::uint64_t kFirstRecheckSeed = 100;
constexpr int kMaxCandidates = 1000;
constexpr std::size_t kMaxSpaceBytes = std::size_t{1} << 20;
const std::set<std::string> kTopLevel = {"name", "description", "seeds", "candidates", "sampler_seed",
                                         "rungs", "trial_config", "keys", "confirmation"};
constexpr std::uint64_t kFirstTuningSeed = 50;  // tables 0-49, tuning 50-99 (the developers' guide)
const std::set<std::string> kKinds = {"log_uniform", "uniform", "choice"};

class SpaceChecker {
 public:
  explicit SpaceChecker(std::string label) : label_(std::move(label)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw std::invalid_argument(printable("space " + label_ + ": " + field + ": " + problem));
  }
  long integer(const json& v, const std::string& field, long lo, long hi) const {
    if (!v.is_number_integer()) fail(field, "expected an integer, got " + json_excerpt(v));
    const long x = v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi) ? hi + 1 : v.get<long>();
    if (x < lo || x > hi) fail(field, "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + v.dump());
    return x;
  }
  std::pair<double, double> range(const json& v, const std::string& field, bool log) const {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
      fail(field, "expected [lo, hi], two numbers, got " + json_excerpt(v));
    const double lo = v[0].get<double>(), hi = v[1].get<double>();
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) fail(field, "expected lo < hi, got " + v.dump());
    if (log && lo <= 0) fail(field, "a log-uniform range must be positive, got " + v.dump());
    return {lo, hi};
  }

 private:
  std::string label_;
};

SpaceKey parse_key(const SpaceChecker& check, const std::string& key, const json& spec) {
  const std::string field = "keys." + key;
  const ConfigKey* k = find_config_key(key);
  if (k == nullptr) check.fail(field, "'" + key + "' is not a config key (docs/algorithms.md lists them)");
  if (k->part == ConfigPart::kScenario)
    check.fail(field, "a scenario key: the trials' datasets come from the scenario as the grid sets it");
  if (!spec.is_object()) check.fail(field, "expected an object, got " + json_excerpt(spec));
  SpaceKey out;
  out.key = key;
  for (const auto& [name, value] : spec.items()) {
    if (name == "algos") {
      if (!value.is_array() || value.empty()) check.fail(field + ".algos", "expected a non-empty array of algorithm names");
      for (const json& a : value) {
        if (!a.is_string()) check.fail(field + ".algos", "expected algorithm names, got " + json_excerpt(a));
        try {
          if (!find_algorithm(a.get<std::string>()).reads(key))
            check.fail(field + ".algos", "'" + a.get<std::string>() + "' does not read '" + key + "'");
        } catch (const std::invalid_argument& e) {
          if (std::string(e.what()).rfind("space ", 0) == 0) throw;
          check.fail(field + ".algos", e.what());
        }
        out.algos.push_back(a.get<std::string>());
      }
      continue;
    }
    if (!kKinds.count(name))
      check.fail(field + "." + name, "unknown key; expected one of algos, choice, log_uniform, uniform");
    if (!out.kind.empty()) check.fail(field, "give one of log_uniform, uniform and choice");
    out.kind = name;
    if (name == "choice") {
      if (!value.is_array() || value.empty()) check.fail(field + ".choice", "expected a non-empty array of values");
      out.choices.assign(value.begin(), value.end());
    } else if (value.is_object()) {
      if (value.empty()) check.fail(field + "." + name, "must not be empty");
      for (const auto& [scenario, r] : value.items())
        out.ranges[scenario] = check.range(r, field + "." + name + "." + scenario, name == "log_uniform");
    } else {
      out.ranges[""] = check.range(value, field + "." + name, name == "log_uniform");
    }
  }
  if (out.kind.empty()) check.fail(field, "give its range: log_uniform, uniform or choice");
  return out;
}

// A random permutation of 0..n−1 from `rng` (Fisher–Yates).
std::vector<int> permutation(int n, Rng& rng) {
  std::vector<int> p(static_cast<std::size_t>(n));
  std::iota(p.begin(), p.end(), 0);
  for (int i = n - 1; i > 0; --i) std::swap(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(rng.uniform() * (i + 1)) % static_cast<std::size_t>(i + 1)]);
  return p;
}

// Candidate k's quantile of `key`: a Latin hypercube over candidates 1..n−1 (each key's range cut
// into n−1 strata, one candidate per stratum, in an order drawn from sampler_seed and the key's
// name), so a handful of candidates still spans every range.
double quantile(const SearchSpace& space, const std::string& key, int k) {
  const int strata = space.candidates - 1;
  Rng rng(space.sampler_seed ^ fnv1a(key));
  const std::vector<int> order = permutation(strata, rng);
  double u = 0;
  for (int i = 1; i <= k; ++i) u = rng.uniform();  // the k-th draw: candidate k's place in its stratum
  return (order[static_cast<std::size_t>(k - 1)] + u) / strata;
}

json three_digits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return std::stod(text);
}

}  // namespace

SearchSpace parse_space(const json& doc, const std::string& label) {
  const SpaceChecker check(label);
  if (!doc.is_object()) check.fail("(top level)", "expected a JSON object");
  for (const auto& [key, value] : doc.items())
    if (!kTopLevel.count(key))
      check.fail(key, "unknown key; expected one of " + comma_joined(std::vector<std::string>(kTopLevel.begin(), kTopLevel.end())));
  for (const char* required : {"name", "seeds", "candidates", "sampler_seed", "rungs", "keys"})
    if (!doc.contains(required)) check.fail(required, "missing");
  SearchSpace s;
  s.document = doc;
  if (!doc["name"].is_string() || !is_safe_name(doc["name"].get<std::string>()))
    check.fail("name", "expected a name of [A-Za-z0-9._-], got " + json_excerpt(doc["name"]));
  s.name = doc["name"].get<std::string>();
  if (doc.contains("description")) {
    if (!doc["description"].is_string()) check.fail("description", "expected a string");
    s.description = doc["description"].get<std::string>();
  }
  if (!doc["seeds"].is_array() || doc["seeds"].empty()) check.fail("seeds", "expected a non-empty array of seeds");
  std::set<std::uint64_t> seen;
  for (std::size_t i = 0; i < doc["seeds"].size(); ++i) {
    const std::string at = "seeds[" + std::to_string(i) + "]";
    const auto seed = static_cast<std::uint64_t>(check.integer(doc["seeds"][i], at, 0, 1L << 40));
    if (seed >= kFirstRecheckSeed)
      check.fail(at, "seed " + std::to_string(seed) + ": seeds from 100 up are reserved for independent rechecks");
    if (!seen.insert(seed).second) check.fail(at, "duplicate seed " + std::to_string(seed));
    s.seeds.push_back(seed);
  }
  s.candidates = static_cast<int>(check.integer(doc["candidates"], "candidates", 1, kMaxCandidates));
  s.sampler_seed = static_cast<std::uint64_t>(check.integer(doc["sampler_seed"], "sampler_seed", 0, 1L << 40));
  if (!doc["rungs"].is_array() || doc["rungs"].empty()) check.fail("rungs", "expected a non-empty array of unit counts");
  for (std::size_t i = 0; i < doc["rungs"].size(); ++i) {
    const int units = static_cast<int>(check.integer(doc["rungs"][i], "rungs[" + std::to_string(i) + "]", 1, 1000));
    if (!s.rungs.empty() && units <= s.rungs.back())
      check.fail("rungs[" + std::to_string(i) + "]", "the units must increase from rung to rung");
    s.rungs.push_back(units);
  }
  if (doc.contains("trial_config")) {
    const json& t = doc["trial_config"];
    if (!t.is_object()) check.fail("trial_config", "expected an object");
    const bool per_scenario = !t.empty() && std::all_of(t.begin(), t.end(), [](const json& v) { return v.is_object(); });
    s.trial_config = per_scenario ? t : json{{"", t}};
    for (const auto& [scenario, overrides] : s.trial_config.items())
      for (const auto& [key, value] : overrides.items()) {
        const ConfigKey* k = find_config_key(key);
        if (k == nullptr || k->part != ConfigPart::kSchedule)
          check.fail("trial_config." + (scenario.empty() ? "" : scenario + ".") + key,
                     "expected a schedule key (the trials' evaluation), got '" + key + "'");
      }
  }
  if (doc.contains("confirmation")) {
    const json& c = doc["confirmation"];
    if (!c.is_object()) check.fail("confirmation", "expected an object with alpha, power and delta");
    for (const auto& [key, value] : c.items()) {
      const std::string field = "confirmation." + key;
      if (key == "alpha" || key == "power") {
        if (!value.is_number() || !(value.get<double>() > 0.0 && value.get<double>() < 1.0))
          check.fail(field, "expected a number between 0 and 1, got " + json_excerpt(value));
        (key == "alpha" ? s.confirmation.alpha : s.confirmation.power) = value.get<double>();
      } else if (key == "delta") {
        const auto positive = [&](const json& v, const std::string& at) {
          if (!v.is_number() || !(v.get<double>() > 0.0) || !std::isfinite(v.get<double>()))
            check.fail(at, "expected a positive number, got " + json_excerpt(v));
          return v.get<double>();
        };
        if (value.is_object()) {
          for (const auto& [scenario, d] : value.items()) s.confirmation.delta[scenario] = positive(d, field + "." + scenario);
        } else {
          s.confirmation.delta[""] = positive(value, field);
        }
      } else {
        check.fail(field, "unknown key; expected alpha, power or delta");
      }
    }
  }
  if (!doc["keys"].is_object() || doc["keys"].empty()) check.fail("keys", "expected an object key → range");
  for (const auto& [key, spec] : doc["keys"].items()) s.keys.push_back(parse_key(check, key, spec));
  if (s.candidates > 1 && s.keys.empty()) check.fail("keys", "candidates beyond the default need keys to vary");
  return s;
}

SearchSpace load_space(const std::string& path) {
  json doc;
  try {
    doc = read_json_input(path, kMaxSpaceBytes);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("space " + path + ": " + e.what());
  }
  return parse_space(doc, path);
}

int max_units(const SearchSpace& space) { return space.rungs.back(); }

std::vector<std::uint64_t> confirmation_seeds(const SearchSpace& space, const std::vector<std::uint64_t>& excluded) {
  std::vector<std::uint64_t> fresh;
  for (std::uint64_t seed = kFirstTuningSeed; seed < kFirstRecheckSeed; ++seed)
    if (std::find(space.seeds.begin(), space.seeds.end(), seed) == space.seeds.end() &&
        std::find(excluded.begin(), excluded.end(), seed) == excluded.end())
      fresh.push_back(seed);
  return fresh;
}

std::vector<std::uint64_t> unit_seeds(const SearchSpace& space, bool uses_prior, int datasets, int units) {
  const int per_unit = uses_prior ? 1 : datasets;
  const std::size_t n = static_cast<std::size_t>(units * per_unit);
  if (n > space.seeds.size())
    throw std::invalid_argument("space " + space.name + ": seeds: " + std::to_string(units) + " units need " +
                                std::to_string(n) + " seeds" + (uses_prior ? "" : " for ddpg (one per dataset and unit)") +
                                ", the space lists " + std::to_string(space.seeds.size()));
  return {space.seeds.begin(), space.seeds.begin() + static_cast<long>(n)};
}

json candidate_overrides(const SearchSpace& space, const std::string& scenario, const std::string& algo, int k) {
  json out = json::object();
  if (k == 0) return out;
  const Algorithm& a = find_algorithm(algo);
  for (const SpaceKey& key : space.keys) {
    if (!a.reads(key.key)) continue;
    if (!key.algos.empty() && std::find(key.algos.begin(), key.algos.end(), algo) == key.algos.end()) continue;
    const double u = quantile(space, key.key, k);
    if (key.kind == "choice") {
      out[key.key] = key.choices[std::min(key.choices.size() - 1, static_cast<std::size_t>(u * key.choices.size()))];
      continue;
    }
    auto it = key.ranges.find("");
    if (it == key.ranges.end()) it = key.ranges.find(scenario);
    if (it == key.ranges.end())
      throw std::invalid_argument("space " + space.name + ": keys." + key.key + "." + key.kind + ": no range for scenario '" +
                                  scenario + "'");
    const auto [lo, hi] = it->second;
    const double x = key.kind == "log_uniform" ? std::exp(std::log(lo) + u * (std::log(hi) - std::log(lo))) : lo + u * (hi - lo);
    const ConfigKey* ck = find_config_key(key.key);
    out[key.key] = ck->type == "integer" ? json(std::lround(x)) : three_digits(x);
  }
  return out;
}

json trial_overrides(const SearchSpace& space, const std::string& scenario) {
  json out = space.trial_config.value("", json::object());
  if (space.trial_config.contains(scenario)) out.update(space.trial_config[scenario]);
  return out;
}

std::vector<int> rung_sizes(const SearchSpace& space) {
  std::vector<int> n = {space.candidates};
  while (n.size() < space.rungs.size()) n.push_back((n.back() + 1) / 2);
  return n;
}

int units_per_search(const SearchSpace& space) {
  const std::vector<int> n = rung_sizes(space);
  int units = 0;
  for (std::size_t i = 0; i < n.size(); ++i) units += n[i] * (space.rungs[i] - (i == 0 ? 0 : space.rungs[i - 1]));
  return units;
}

}  // namespace rapid
