// A multi-layer perceptron built from a list of layers, with forward and backward passes on a
// batch (one sample per column).
//
// All parameters live in one contiguous vector (and their gradients in another), so the
// optimiser, the Polyak soft update and save/load each work on a single array. Layers hold
// offsets into it, which also makes an Mlp copyable with `=` (how target networks are made).
//
// Buffers are sized on the first call at a given batch size; later calls at that size allocate
// nothing. To keep the working set small (training interleaves the networks with SUMO, and both
// compete for the same caches), ReLU and Tanh run in place on the previous layer's output where
// nobody needs that output any more, LayerNorm normalises a Linear output in place, and the
// backward pass runs through two scratch gradient buffers instead of one per layer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "core/tensor.hpp"

namespace rapid {

enum class LayerKind { kLinear, kLayerNorm, kReLU, kTanh };

// What a backward pass computes: the parameter gradients (added into grads()), the gradient with
// respect to the network input (returned), or both. Asking only for what is read saves the first
// layer's input-gradient GEMM or every weight-gradient GEMM.
enum class Grads { kParamsAndInput, kParamsOnly, kInputOnly };

// How a network's Linear layers start (LayerNorm always starts at scale 1, shift 0). Each is the
// scheme of a published code base, so a published method can start as it did there:
//   kDdpg     Lillicrap et al. 2016 (§7): weights and biases U(±1/√fan_in), the last layer's
//             U(±3e-3) (a small output keeps the initial policy and Q near zero); the paper's five.
//   kXavier   Glorot-uniform weights U(±√(6/(fan_in + fan_out))), zero biases: flax's
//             xavier_uniform, ikostrikov/rlpd's default_init for every Dense, heads included.
//   kPytorch  torch.nn.Linear's own reset_parameters: weights and biases U(±1/√fan_in) in every
//             layer, the last included; sfujim/TD3_BC never overrides it.
enum class WeightInit { kDdpg, kXavier, kPytorch };
// Their names in configs and records ("ddpg", "xavier", "pytorch"), in the enum's order.
const std::vector<std::string>& weight_init_names();
const std::string& weight_init_name(WeightInit scheme);
// The scheme of a name; nullopt for any other.
std::optional<WeightInit> weight_init_from_name(const std::string& name);

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

  // Draws every parameter by `scheme` (WeightInit), layer by layer from `rng`. The last Linear
  // layer may stand for `output_heads` side-by-side heads of equal width (SAC's means and log
  // stds): Xavier then counts one head's width as its fan-out, as two separate Dense layers would.
  void init(Rng& rng, WeightInit scheme = WeightInit::kDdpg, int output_heads = 1);

  // Forward pass; the returned reference stays valid until the next forward.
  const Mat& forward(const ConstMatRef& x);
  // Backward pass from dL/d(output) of the last forward. Adds dL/dθ into grads() unless `which`
  // is kInputOnly (so zero_grad() first), and returns dL/d(input) (an empty matrix for
  // kParamsOnly). The returned reference stays valid until the next backward.
  const Mat& backward(const ConstMatRef& dy, Grads which = Grads::kParamsAndInput);
  const Mat& output() const { return acts_[layers_.back().dst]; }

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

  // The same network keeping only the first `count` outputs of its last Linear layer (whatever
  // followed that layer is dropped), then tanh if `tanh_output`: SAC's evaluation policy, tanh of
  // the mean half of its Gaussian head. copy_first_outputs_to refreshes such a network's
  // parameters from this one without allocating.
  Mlp first_outputs(int count, bool tanh_output) const;
  void copy_first_outputs_to(Mlp& dst) const;

  // this ← τ·source + (1−τ)·this (source must have the same architecture).
  void soft_update_from(const Mlp& source, float tau);

  // Binary checkpoint: architecture, parameters and `updates`, the number of gradient steps that
  // made them (what a reader needs to know the network has learned at all); load() checks the
  // file fully and throws std::runtime_error naming the problem, and puts the count in *updates
  // (-1 for a checkpoint of format 1, which predates the count). save() writes atomically (temp
  // file + rename).
  void save(const std::string& path, std::int64_t updates) const;
  static Mlp load(const std::string& path, std::int64_t* updates = nullptr);

 private:
  // Activations live in acts_, a layer names its buffers by index (so `=` copies stay valid).
  static constexpr int kCallerInput = -1;  // src of the first layer: the caller's x
  struct Layer {
    LayerKind kind;
    int in = 0, out = 0;
    int w_off = 0, b_off = 0;  // Linear: W (out×in), b (out). LayerNorm: gain, shift (out each).
    int src = kCallerInput;    // buffer holding this layer's input
    int dst = 0;               // buffer holding its output (== src when it runs in place)
    int xhat = 0;              // LayerNorm: buffer of the normalised input (== src when in place)
    RowVec inv_std;            // LayerNorm: 1/√(var + eps) per sample
    RowVec tmp1, tmp2;         // LayerNorm per-sample reductions
  };
  using GradMap = Eigen::Map<Mat, Eigen::AlignedMax>;

  // Decides which buffer every layer reads and writes (see the class comment).
  void plan_buffers();
  const Mat& input_of(const Layer& l) const { return l.src == kCallerInput ? input_ : acts_[l.src]; }
  void forward_layer(Layer& l);
  // Turns the gradient in scratch buffer `buf` (w.r.t. l's output) into the gradient w.r.t. l's
  // input: in place, or into the other scratch buffer (Linear); returns the buffer holding it.
  int backward_layer(Layer& l, int buf, Eigen::Index batch, bool param_grads, bool input_grad);
  GradMap grad_map(int which, Eigen::Index rows, Eigen::Index cols);

  int input_dim_ = 0, output_dim_ = 0, max_width_ = 0;
  std::vector<LayerSpec> specs_;
  std::vector<Layer> layers_;
  std::vector<Mat> acts_;
  Mat input_;          // a copy of the caller's x from the last forward (Linear needs it for dW)
  Vec grad_buf_[2];    // the backward pass's two scratch gradients, max_width × batch each
  Mat input_grad_;     // dL/d(input) handed back by backward()
  Vec params_, grads_;
};

}  // namespace rapid
