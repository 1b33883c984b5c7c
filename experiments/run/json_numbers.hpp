// JSON cannot hold NaN or inf: the records and reports write such values (a BC loss without a
// prior buffer, a statistic of no runs) as null, and read null back as no number.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/statistics.hpp"

namespace rapid {

inline nlohmann::json json_number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

inline nlohmann::json json_number(std::optional<double> x) { return x ? json_number(*x) : nlohmann::json(nullptr); }

// `v` as a double when it is a number; nullopt for null or anything else. The second form reads
// `object[key]`, nullopt when `object` is not an object or has no such key.
inline std::optional<double> optional_number(const nlohmann::json& v) {
  return v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
}
inline std::optional<double> optional_number(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) ? optional_number(object[key]) : std::nullopt;
}

// [lo, hi], or null when there is no interval.
inline nlohmann::json json_interval(const std::optional<Interval>& i) {
  return i ? nlohmann::json::array({i->lo, i->hi}) : nlohmann::json(nullptr);
}

}  // namespace rapid
