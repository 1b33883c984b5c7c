#include "algos/method_key.hpp"

#include <algorithm>
#include <stdexcept>

namespace rapid {

void MethodValues::set(const MethodKey& key, double value) {
  const double held = key.type == MethodKey::kInteger ? static_cast<double>(static_cast<int>(value))
                                                      : static_cast<double>(static_cast<float>(value));
  for (auto& [name, v] : values_)
    if (name == key.name) {
      v = held;
      return;
    }
  values_.emplace_back(std::string(key.name), held);
}

double MethodValues::get(const MethodKey& key) const {
  for (const auto& [name, v] : values_)
    if (name == key.name) return v;
  if (!key.neutral) throw std::logic_error("method key '" + std::string(key.name) + "' has no value (a required key)");
  return *key.neutral;
}

bool MethodValues::has(const std::string& name) const {
  return std::any_of(values_.begin(), values_.end(), [&](const auto& entry) { return entry.first == name; });
}

void MethodValues::erase(const std::string& name) {
  std::erase_if(values_, [&](const auto& entry) { return entry.first == name; });
}

}  // namespace rapid
