#include "core/gemm_log.hpp"

#include <stdexcept>

namespace rapid {

GemmLog* GemmLog::active_ = nullptr;

GemmLog::GemmLog() {
  if (active_ != nullptr) throw std::logic_error("GemmLog: a log is already recording");
  active_ = this;
}

GemmLog::~GemmLog() { active_ = nullptr; }

double total_flops(const std::vector<GemmShape>& gemms) {
  double f = 0;
  for (const GemmShape& s : gemms) f += s.flops();
  return f;
}

}  // namespace rapid
