// JSON cannot hold NaN or inf: the records and reports write such values (a BC loss without a
// prior buffer, a statistic of no runs) as null.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/statistics.hpp"

namespace rapid {

inline nlohmann::json json_number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

inline nlohmann::json json_number(std::optional<double> x) { return x ? json_number(*x) : nlohmann::json(nullptr); }

// [lo, hi], or null when there is no interval.
inline nlohmann::json json_interval(const std::optional<Interval>& i) {
  return i ? nlohmann::json::array({i->lo, i->hi}) : nlohmann::json(nullptr);
}

}  // namespace rapid
