#include "experiments/sweep/aggregate_claim.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "core/json_input.hpp"
#include "experiments/sweep/claim_fields.hpp"

namespace rapid {

extern const char* const kRegisteredClaimsJson;  // experiments/claims/confirmatory.json (generated source)

namespace {

using nlohmann::json;

using claim_fields::fail;
using claim_fields::text;

// A fixed-value key: absent, or exactly `value` (the only analysis implemented).
void fixed_value(const json& j, const std::string& key, const std::string& value, const std::string& field) {
  if (j.contains(key) && j[key] != value)
    fail(field + "." + key, "expected \"" + value + "\" (the only one implemented), got " + json_excerpt(j[key]));
}

std::uint64_t seed_bound(const json& seeds, const char* key, const std::string& field) {
  const json v = seeds.value(key, json());
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
  fail(field + ".seeds." + key, "expected a non-negative integer, got " + json_excerpt(v));
}

}  // namespace

std::string AggregateClaimSpec::seeds_text() const {
  if (!first_seed && !last_seed) return "every seed";
  return "seeds " + std::to_string(first_seed.value_or(0)) + "-" + (last_seed ? std::to_string(*last_seed) : "");
}

bool is_aggregate_claim(const json& j) { return j.is_object() && j.contains("kind") && j["kind"] == "aggregate"; }

AggregateClaimSpec parse_aggregate_claim(const json& j, const std::string& field) {
  if (!j.is_object()) fail(field, "expected an object, got " + json_excerpt(j));
  static const std::set<std::string> known = {"id", "statement", "definition", "kind", "x", "y", "metric",
                                              "rows", "unit", "pairing", "margin", "seeds"};
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) fail(field + "." + key, "unknown key for an aggregate claim");
  AggregateClaimSpec c;
  c.id = text(j, "id", field);
  c.statement = text(j, "statement", field);
  c.x = text(j, "x", field);
  c.y = text(j, "y", field);
  if (c.x == c.y) fail(field + ".y", "is x ('" + c.x + "'): a claim compares two algorithms");
  fixed_value(j, "metric", "final return", field);
  fixed_value(j, "rows", "all", field);
  fixed_value(j, "unit", "delta", field);
  fixed_value(j, "pairing", "seed", field);
  if (j.contains("margin")) {
    if (!j["margin"].is_number() || !std::isfinite(j["margin"].get<double>()) || !(j["margin"].get<double>() > 0.0))
      fail(field + ".margin", "expected a positive number (δ units), got " + json_excerpt(j["margin"]));
    c.margin = j["margin"].get<double>();
  }
  if (j.contains("seeds")) {
    const json& s = j["seeds"];
    if (!s.is_object() || s.size() != 2 || !s.contains("first") || !s.contains("last"))
      fail(field + ".seeds", "expected {\"first\": N, \"last\": M}, got " + json_excerpt(s));
    c.first_seed = seed_bound(s, "first", field);
    c.last_seed = seed_bound(s, "last", field);
    if (*c.last_seed < *c.first_seed) fail(field + ".seeds", "last is below first");
  }
  return c;
}

std::vector<AggregateClaimSpec> registered_aggregate_claims(const std::string& grid_name) {
  static const json doc = [] {
    try {
      return json::parse(kRegisteredClaimsJson);
    } catch (const std::exception& e) {
      throw std::logic_error(std::string("experiments/claims/confirmatory.json: ") + e.what());
    }
  }();
  std::vector<AggregateClaimSpec> out;
  if (doc.value("grid", "") != grid_name) return out;
  try {
    for (std::size_t i = 0; i < doc.at("claims").size(); ++i) {
      out.push_back(parse_aggregate_claim(doc["claims"][i], "claims[" + std::to_string(i) + "]"));
      out.back().registered = true;
    }
  } catch (const std::exception& e) {
    throw std::logic_error(std::string("experiments/claims/confirmatory.json: ") + e.what());
  }
  return out;
}

}  // namespace rapid
