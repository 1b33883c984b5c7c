#include "experiments/sweep/claim_fields.hpp"

#include <stdexcept>

#include "core/json_input.hpp"

namespace rapid::claim_fields {

void fail(const std::string& field, const std::string& problem) { throw std::invalid_argument(field + ": " + problem); }

std::string text(const nlohmann::json& j, const std::string& key, const std::string& field) {
  if (!j.contains(key)) fail(field + "." + key, "missing");
  if (!j[key].is_string() || j[key].get<std::string>().empty())
    fail(field + "." + key, "expected a non-empty string, got " + json_excerpt(j[key]));
  return j[key].get<std::string>();
}

}  // namespace rapid::claim_fields
