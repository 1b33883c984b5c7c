// CoL-all: RLPD plus λ_BC times the mean imitation error over the whole batch, online half
// included (so it also imitates its own early, poor actions).
#pragma once

#include "algos/rlpd.hpp"

namespace rapid {

class ColAll : public Rlpd {
 public:
  using Rlpd::Rlpd;
  std::string name() const override { return "col-all"; }

 protected:
  void bc_weights(const Batch& batch, RowVec& w) const override {
    w.setConstant(batch.size(), config().lambda_bc);
  }
};

}  // namespace rapid
