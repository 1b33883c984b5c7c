// Reading a claim's fields, for both kinds of claim files (claim_spec.cpp: the paper's and a
// grid's claims; aggregate_claim.cpp: the aggregate ones): a wrong field is one line, "FIELD:
// problem", as a std::invalid_argument the caller prefixes with the file.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace rapid::claim_fields {

[[noreturn]] void fail(const std::string& field, const std::string& problem);

// j[key] as a non-empty string; `field` names j ("claims[2]").
std::string text(const nlohmann::json& j, const std::string& key, const std::string& field);

}  // namespace rapid::claim_fields
