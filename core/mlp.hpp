// A multi-layer perceptron built from a list of layers, with forward and backward passes on a
// batch (one sample per column).
//
// All parameters live in one contiguous vector (and their gradients in another), so the
// optimiser, the Polyak soft update and save/load each work on a single array. Layers hold
// offsets into it, which also makes an Mlp copyable with `=` (how target networks are made).
//
// Buffers are sized on the first call at a given batch size; later calls at that size allocate
// nothing.
#pragma once

#include <string>
#include <vector>

#include "core/rng.hpp"
#include "core/tensor.hpp"

namespace rapid {

enum class LayerKind { kLinear, kLayerNorm, kReLU, kTanh };

struct LayerSpec {
  LayerKind kind;
  int out = 0;  // output width; only read for kLinear (the others keep their input width)
};

class Mlp {
 public:
  Mlp() = default;
  Mlp(int input_dim, const std::vector<LayerSpec>& layers);

  // The usual shape: Linear → [LayerNorm] → ReLU per hidden width, then a Linear output layer
  // followed by tanh if `tanh_output`.
  static Mlp make(int input_dim, const std::vector<int>& hidden, int output_dim, bool layer_norm,
                  bool tanh_output);

  // Fan-in uniform initialisation U(-1/√fan_in, 1/√fan_in) for hidden Linear layers, and
  // U(-final_scale, final_scale) for the last Linear layer (DDPG's small output init keeps the
  // initial policy and Q near zero). LayerNorm starts at scale 1, shift 0.
  void init(Rng& rng, float final_scale = 3e-3f);

  // Forward pass; the returned reference stays valid until the next forward.
  const Mat& forward(const ConstMatRef& x);
  // Backward pass from dL/d(output) of the last forward. Adds dL/dθ into grads() when
  // `param_grads` (so zero_grad() first), and returns dL/d(input).
  const Mat& backward(const ConstMatRef& dy, bool param_grads = true);
  const Mat& output() const { return layers_.back().y; }

  void zero_grad() { grads_.setZero(); }
  Vec& params() { return params_; }
  const Vec& params() const { return params_; }
  Vec& grads() { return grads_; }
  const Vec& grads() const { return grads_; }

  int input_dim() const { return input_dim_; }
  int output_dim() const { return output_dim_; }
  const std::vector<LayerSpec>& specs() const { return specs_; }
  bool same_architecture(const Mlp& other) const;
  // Human-readable layer list, e.g. "19-Linear128-LN-ReLU-Linear2-Tanh".
  std::string describe() const;

  // this ← τ·source + (1−τ)·this (source must have the same architecture).
  void soft_update_from(const Mlp& source, float tau);

  // Binary checkpoint: architecture and parameters; load() checks the file fully and throws
  // std::runtime_error naming the problem. save() writes atomically (temp file + rename).
  void save(const std::string& path) const;
  static Mlp load(const std::string& path);

 private:
  struct Layer {
    LayerKind kind;
    int in = 0, out = 0;
    int w_off = 0, b_off = 0;  // Linear: W (out×in), b (out). LayerNorm: gain, shift (out each).
    Mat x;       // first layer only: the caller's input of the last forward (Linear needs it for dW)
    Mat y;       // output of the last forward
    Mat dx;      // dL/d(input) of the last backward
    Mat xhat;    // LayerNorm: normalised input
    RowVec inv_std;  // LayerNorm: 1/√(var + eps) per sample
    RowVec tmp1, tmp2;  // LayerNorm backward per-sample reductions
  };

  void forward_layer(Layer& l, const ConstMatRef& x);
  void backward_layer(Layer& l, const ConstMatRef& dy, bool param_grads);

  int input_dim_ = 0, output_dim_ = 0;
  std::vector<LayerSpec> specs_;
  std::vector<Layer> layers_;
  Vec params_, grads_;
};

}  // namespace rapid
