#include "core/mlp.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "core/gemm_log.hpp"
#include "core/hash.hpp"

namespace rapid {

namespace {
// Every process that links the networks plans Eigen's products for the same caches, set here
// before main() so that no product runs first (core/tensor.hpp says why).
[[maybe_unused]] const bool kProductsPlanned = [] {
  Eigen::setCpuCacheSizes(kPlannedL1CacheBytes, kPlannedL2CacheBytes, kPlannedL3CacheBytes);
  return true;
}();

constexpr float kLayerNormEps = 1e-5f;
constexpr char kMagic[8] = {'R', 'A', 'P', 'I', 'D', 'M', 'L', 'P'};
// Format 2 added the update count after the version; format 1 files still load.
constexpr std::uint32_t kFormatVersion = 2;

const char* kind_name(LayerKind k) {
  switch (k) {
    case LayerKind::kLinear: return "Linear";
    case LayerKind::kLayerNorm: return "LN";
    case LayerKind::kReLU: return "ReLU";
    case LayerKind::kTanh: return "Tanh";
  }
  return "?";
}

}  // namespace

const std::vector<std::string>& weight_init_names() {
  static const std::vector<std::string> names = {"ddpg", "xavier", "pytorch"};
  return names;
}

const std::string& weight_init_name(WeightInit scheme) { return weight_init_names()[static_cast<int>(scheme)]; }

std::optional<WeightInit> weight_init_from_name(const std::string& name) {
  const std::vector<std::string>& names = weight_init_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<WeightInit>(it - names.begin());
}

Mlp::Mlp(int input_dim, const std::vector<LayerSpec>& layers) : input_dim_(input_dim), specs_(layers) {
  if (input_dim <= 0) throw std::invalid_argument("Mlp: input dimension must be positive");
  if (layers.empty()) throw std::invalid_argument("Mlp: no layers");
  int width = input_dim;
  int offset = 0;
  for (const LayerSpec& s : layers) {
    Layer l;
    l.kind = s.kind;
    l.in = width;
    if (s.kind == LayerKind::kLinear) {
      if (s.out <= 0) throw std::invalid_argument("Mlp: Linear layer needs a positive width");
      l.out = s.out;
      l.w_off = offset;
      offset += l.out * l.in;
      l.b_off = offset;
      offset += l.out;
    } else if (s.kind == LayerKind::kLayerNorm) {
      l.out = width;
      l.w_off = offset;
      offset += width;
      l.b_off = offset;
      offset += width;
    } else {
      l.out = width;
    }
    width = l.out;
    layers_.push_back(std::move(l));
  }
  output_dim_ = width;
  params_ = Vec::Zero(offset);
  grads_ = Vec::Zero(offset);
  plan_buffers();
  for (Layer& l : layers_)
    if (l.kind == LayerKind::kLayerNorm) params_.segment(l.w_off, l.out).setOnes();
}

Mlp Mlp::make(int input_dim, const std::vector<int>& hidden, int output_dim, bool layer_norm,
              bool tanh_output) {
  std::vector<LayerSpec> specs;
  for (int h : hidden) {
    specs.push_back({LayerKind::kLinear, h});
    if (layer_norm) specs.push_back({LayerKind::kLayerNorm});
    specs.push_back({LayerKind::kReLU});
  }
  specs.push_back({LayerKind::kLinear, output_dim});
  if (tanh_output) specs.push_back({LayerKind::kTanh});
  return Mlp(input_dim, specs);
}

void Mlp::init(Rng& rng, WeightInit scheme, int output_heads) {
  int last_linear = -1;
  for (int i = 0; i < static_cast<int>(layers_.size()); ++i)
    if (layers_[i].kind == LayerKind::kLinear) last_linear = i;
  if (output_heads < 1 || layers_[last_linear].out % output_heads != 0)
    throw std::invalid_argument("Mlp::init: " + std::to_string(layers_[last_linear].out) + " outputs are not " +
                                std::to_string(output_heads) + " heads of equal width");
  for (int i = 0; i < static_cast<int>(layers_.size()); ++i) {
    const Layer& l = layers_[i];
    if (l.kind == LayerKind::kLinear) {
      const int weights = l.out * l.in;
      const double fan_in_bound = 1.0 / std::sqrt(double(l.in));
      if (scheme == WeightInit::kXavier) {
        const int fan_out = i == last_linear ? l.out / output_heads : l.out;
        const double bound = std::sqrt(6.0 / double(l.in + fan_out));
        for (int k = 0; k < weights; ++k) params_[l.w_off + k] = static_cast<float>(rng.uniform(-bound, bound));
        params_.segment(l.b_off, l.out).setZero();
        continue;
      }
      // kDdpg and kPytorch draw weights then biases from one bound; they differ in the last layer.
      // DDPG's 3e-3 is the float it always was, widened (the paper's five keep their bits).
      constexpr double kDdpgFinal = static_cast<double>(3e-3f);
      const double bound = (i == last_linear && scheme == WeightInit::kDdpg) ? kDdpgFinal : fan_in_bound;
      for (int k = 0; k < weights + l.out; ++k)
        params_[l.w_off + k] = static_cast<float>(rng.uniform(-bound, bound));
    } else if (l.kind == LayerKind::kLayerNorm) {
      params_.segment(l.w_off, l.out).setOnes();
      params_.segment(l.b_off, l.out).setZero();
    }
  }
}

Mlp Mlp::first_outputs(int count, bool tanh_output) const {
  int last_linear = -1;
  for (int i = 0; i < static_cast<int>(specs_.size()); ++i)
    if (specs_[i].kind == LayerKind::kLinear) last_linear = i;
  if (count <= 0 || count > layers_[last_linear].out)
    throw std::invalid_argument("Mlp::first_outputs: " + std::to_string(count) + " of " +
                                std::to_string(layers_[last_linear].out) + " outputs");
  std::vector<LayerSpec> specs(specs_.begin(), specs_.begin() + last_linear + 1);
  specs.back().out = count;
  if (tanh_output) specs.push_back({LayerKind::kTanh});
  Mlp sliced(input_dim_, specs);
  copy_first_outputs_to(sliced);
  return sliced;
}

void Mlp::copy_first_outputs_to(Mlp& dst) const {
  // Every layer before the last Linear is the same, so its parameters are a common prefix.
  int last_linear = -1;
  for (int i = 0; i < static_cast<int>(layers_.size()); ++i)
    if (layers_[i].kind == LayerKind::kLinear) last_linear = i;
  const Layer& src = layers_[last_linear];
  const Layer& out = dst.layers_[last_linear];
  dst.params_.head(src.w_off) = params_.head(src.w_off);
  Eigen::Map<const Mat> w(params_.data() + src.w_off, src.out, src.in);
  Eigen::Map<Mat>(dst.params_.data() + out.w_off, out.out, out.in) = w.topRows(out.out);
  dst.params_.segment(out.b_off, out.out) = params_.segment(src.b_off, out.out);
}

void Mlp::plan_buffers() {
  // May layer i+1 overwrite layer i's output? Only if layer i's backward does not read it: a
  // Linear reads its input, LayerNorm its x̂, ReLU and Tanh their own output. The caller's x is
  // never overwritten (it is const; the first layer works from a copy or its own buffer).
  auto new_buffer = [this] {
    acts_.emplace_back();
    return static_cast<int>(acts_.size()) - 1;
  };
  int prev = kCallerInput;
  bool prev_free = false;  // whether the buffer `prev` may be overwritten by the next layer
  max_width_ = input_dim_;
  for (Layer& l : layers_) {
    l.src = prev;
    max_width_ = std::max(max_width_, l.out);
    switch (l.kind) {
      case LayerKind::kLinear:
        l.dst = new_buffer();
        prev_free = true;
        break;
      case LayerKind::kLayerNorm:
        l.xhat = prev_free ? prev : new_buffer();
        l.dst = new_buffer();
        prev_free = true;
        break;
      case LayerKind::kReLU:
      case LayerKind::kTanh:
        l.dst = prev_free ? prev : new_buffer();
        prev_free = false;
        break;
    }
    prev = l.dst;
  }
}

void Mlp::forward_layer(Layer& l) {
  const Mat& x = input_of(l);
  Mat& y = acts_[l.dst];
  const Eigen::Index batch = x.cols();
  switch (l.kind) {
    case LayerKind::kLinear: {
      Eigen::Map<const Mat> W(params_.data() + l.w_off, l.out, l.in);
      Eigen::Map<const Vec> b(params_.data() + l.b_off, l.out);
      y.resize(l.out, batch);
      y.noalias() = W * x;
      GemmLog::note(GemmShape::kForward, l.out, l.in, batch);
      y.colwise() += b;
      break;
    }
    case LayerKind::kLayerNorm: {
      Eigen::Map<const Vec> gain(params_.data() + l.w_off, l.out);
      Eigen::Map<const Vec> shift(params_.data() + l.b_off, l.out);
      Mat& xhat = acts_[l.xhat];
      l.tmp1 = x.colwise().mean();
      xhat = x.rowwise() - l.tmp1;  // coefficient-wise, so also right when xhat is x
      l.inv_std = (xhat.array().square().colwise().mean() + kLayerNormEps).rsqrt().matrix();
      xhat.array().rowwise() *= l.inv_std.array();
      y = xhat;
      y.array().colwise() *= gain.array();
      y.colwise() += shift;
      break;
    }
    // Coefficient-wise, so also right when y is x (in place).
    case LayerKind::kReLU:
      y = x.cwiseMax(0.0f);
      break;
    case LayerKind::kTanh:
      y = x.array().tanh().matrix();
      break;
  }
}

const Mat& Mlp::forward(const ConstMatRef& x) {
  if (x.rows() != input_dim_)
    throw std::invalid_argument("Mlp::forward: input has " + std::to_string(x.rows()) +
                                " rows, network expects " + std::to_string(input_dim_));
  input_ = x;
  for (Layer& l : layers_) forward_layer(l);
  return output();
}

Mlp::GradMap Mlp::grad_map(int which, Eigen::Index rows, Eigen::Index cols) {
  return GradMap(grad_buf_[which].data(), rows, cols);
}

int Mlp::backward_layer(Layer& l, int buf, Eigen::Index batch, bool param_grads, bool input_grad) {
  GradMap g = grad_map(buf, l.out, batch);
  const Mat& y = acts_[l.dst];
  switch (l.kind) {
    case LayerKind::kLinear: {
      Eigen::Map<const Mat> W(params_.data() + l.w_off, l.out, l.in);
      if (param_grads) {
        Eigen::Map<Mat> dW(grads_.data() + l.w_off, l.out, l.in);
        Eigen::Map<Vec> db(grads_.data() + l.b_off, l.out);
        dW.noalias() += g * input_of(l).transpose();
        GemmLog::note(GemmShape::kWeightGrad, l.out, l.in, batch);
        db += g.rowwise().sum();
      }
      if (!input_grad) return buf;
      GradMap dx = grad_map(1 - buf, l.in, batch);
      dx.noalias() = W.transpose() * g;
      GemmLog::note(GemmShape::kInputGrad, l.out, l.in, batch);
      return 1 - buf;
    }
    case LayerKind::kLayerNorm: {
      // y = gain⊙x̂ + shift with x̂ = (x−μ)/σ per sample. With h = gain⊙dy:
      // dx = (h − mean(h) − x̂·mean(h⊙x̂)) / σ.
      Eigen::Map<const Vec> gain(params_.data() + l.w_off, l.out);
      const Mat& xhat = acts_[l.xhat];
      if (param_grads) {
        Eigen::Map<Vec> dgain(grads_.data() + l.w_off, l.out);
        Eigen::Map<Vec> dshift(grads_.data() + l.b_off, l.out);
        dgain += (g.array() * xhat.array()).rowwise().sum().matrix();
        dshift += g.rowwise().sum();
      }
      g.array().colwise() *= gain.array();
      l.tmp1 = g.colwise().mean();
      l.tmp2 = (g.array() * xhat.array()).colwise().mean().matrix();
      g.rowwise() -= l.tmp1;
      g.array() -= xhat.array().rowwise() * l.tmp2.array();
      g.array().rowwise() *= l.inv_std.array();
      return buf;
    }
    case LayerKind::kReLU:
      g = (y.array() > 0.0f).select(g.array(), 0.0f).matrix();
      return buf;
    case LayerKind::kTanh:
      g.array() *= 1.0f - y.array().square();
      return buf;
  }
  return buf;
}

const Mat& Mlp::backward(const ConstMatRef& dy, Grads which) {
  static const Mat kNoInputGrad;
  const Eigen::Index batch = output().cols();
  if (dy.rows() != output_dim_ || dy.cols() != batch)
    throw std::invalid_argument("Mlp::backward: gradient shape does not match the last forward");
  const bool param_grads = which != Grads::kInputOnly;
  const bool input_grad = which != Grads::kParamsOnly;
  for (Vec& buf : grad_buf_) buf.resize(static_cast<Eigen::Index>(max_width_) * batch);
  grad_map(0, output_dim_, batch) = dy;
  int buf = 0;
  for (int i = static_cast<int>(layers_.size()) - 1; i >= 0; --i) {
    // Nobody reads the first layer's input gradient unless the caller asked for it.
    buf = backward_layer(layers_[i], buf, batch, param_grads, /*input_grad=*/i > 0 || input_grad);
  }
  if (!input_grad) return kNoInputGrad;
  input_grad_ = grad_map(buf, input_dim_, batch);
  return input_grad_;
}

bool Mlp::same_architecture(const Mlp& other) const {
  if (input_dim_ != other.input_dim_ || layers_.size() != other.layers_.size()) return false;
  for (std::size_t i = 0; i < layers_.size(); ++i)
    if (layers_[i].kind != other.layers_[i].kind || layers_[i].out != other.layers_[i].out) return false;
  return true;
}

std::string Mlp::describe() const {
  std::string s = std::to_string(input_dim_);
  for (const Layer& l : layers_) {
    s += '-';
    s += kind_name(l.kind);
    if (l.kind == LayerKind::kLinear) s += std::to_string(l.out);
  }
  return s;
}

void Mlp::soft_update_from(const Mlp& source, float tau) {
  if (!same_architecture(source)) throw std::invalid_argument("soft update between different networks");
  params_ = tau * source.params_ + (1.0f - tau) * params_;
}

void Mlp::save(const std::string& path, std::int64_t updates) const {
  std::string buf(kMagic, sizeof kMagic);
  auto put = [&buf](const auto& v) { buf.append(reinterpret_cast<const char*>(&v), sizeof v); };
  put(kFormatVersion);
  put(updates);
  put(static_cast<std::int32_t>(input_dim_));
  put(static_cast<std::int32_t>(specs_.size()));
  for (const LayerSpec& s : specs_) {
    put(static_cast<std::int32_t>(s.kind));
    put(static_cast<std::int32_t>(s.kind == LayerKind::kLinear ? s.out : 0));
  }
  put(static_cast<std::int64_t>(params_.size()));
  buf.append(reinterpret_cast<const char*>(params_.data()), sizeof(float) * params_.size());
  put(fnv1a(buf));
  write_file_atomic(path, buf);
}

Mlp Mlp::load(const std::string& path, std::int64_t* updates) {
  const std::string buf = read_file(path);
  std::size_t pos = 0;
  auto fail = [&path](const std::string& why) -> void {
    throw std::runtime_error("checkpoint " + path + ": " + why);
  };
  auto get = [&](auto& v) {
    if (pos + sizeof v > buf.size()) fail("truncated");
    std::memcpy(&v, buf.data() + pos, sizeof v);
    pos += sizeof v;
  };
  if (buf.size() < sizeof kMagic || std::memcmp(buf.data(), kMagic, sizeof kMagic) != 0)
    fail("not a rapid network checkpoint");
  pos = sizeof kMagic;
  std::uint32_t version = 0;
  get(version);
  if (version != 1 && version != kFormatVersion) fail("unsupported format version " + std::to_string(version));
  std::int64_t stored_updates = -1;
  if (version >= 2) {
    get(stored_updates);
    if (stored_updates < 0) fail("corrupt header (negative update count)");
  }
  std::int32_t input_dim = 0, n_layers = 0;
  get(input_dim);
  get(n_layers);
  if (input_dim <= 0 || n_layers <= 0 || n_layers > 1000) fail("corrupt header");
  std::vector<LayerSpec> specs;
  for (int i = 0; i < n_layers; ++i) {
    std::int32_t kind = 0, out = 0;
    get(kind);
    get(out);
    if (kind < 0 || kind > static_cast<int>(LayerKind::kTanh)) fail("unknown layer kind");
    specs.push_back({static_cast<LayerKind>(kind), out});
  }
  Mlp net(input_dim, specs);
  std::int64_t n_params = 0;
  get(n_params);
  if (n_params != net.params_.size()) fail("parameter count does not match its architecture");
  const std::size_t bytes = sizeof(float) * static_cast<std::size_t>(n_params);
  if (pos + bytes + sizeof(std::uint64_t) != buf.size()) fail("truncated or has trailing data");
  std::memcpy(net.params_.data(), buf.data() + pos, bytes);
  pos += bytes;
  const std::uint64_t expected = fnv1a(std::string_view(buf).substr(0, pos));
  std::uint64_t stored = 0;
  get(stored);
  if (stored != expected) fail("checksum mismatch (corrupt file)");
  if (updates != nullptr) *updates = stored_updates;
  return net;
}

}  // namespace rapid
