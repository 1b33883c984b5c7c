// Adam (Kingma & Ba 2015) with bias correction, on one flat parameter vector.
#pragma once

#include "core/tensor.hpp"

namespace rapid {

struct AdamConfig {
  float lr = 1e-3f;
  float beta1 = 0.9f;
  float beta2 = 0.999f;
  float eps = 1e-8f;
};

class Adam {
 public:
  Adam() = default;
  Adam(Eigen::Index n_params, AdamConfig config);
  // θ ← θ − lr · m̂ / (√v̂ + eps), with m, v the running moments of the gradient.
  void step(Vec& params, const Vec& grads);
  long steps() const { return t_; }
  const AdamConfig& config() const { return config_; }

 private:
  AdamConfig config_;
  Vec m_, v_;
  long t_ = 0;
};

}  // namespace rapid
