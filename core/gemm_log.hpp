// The matrix products the networks run, recorded on request: `rapid bench` times an update
// against the same products run plain, so the products must be the ones the update really ran
// (an ensemble's members, a delayed actor, a stochastic actor's wider head), not a model of them.
#pragma once

#include <vector>

namespace rapid {

// One matrix product C (m×n) = op(A) op(B) with inner dimension k: 2·m·n·k FLOPs.
struct GemmShape {
  enum Kind { kForward, kWeightGrad, kInputGrad } kind;  // W·X, dY·Xᵀ (accumulated), Wᵀ·dY
  int out, in, batch;                                     // of the Linear layer it belongs to
  double flops() const { return 2.0 * out * in * batch; }
};

// While one is alive, every Linear layer's product is appended to it, in the order they run.
// At most one at a time, and only while one thread runs networks (a recording is for the bench,
// which records single-threaded; the ensemble's OpenMP loop would interleave the members).
class GemmLog {
 public:
  GemmLog();
  ~GemmLog();
  GemmLog(const GemmLog&) = delete;
  GemmLog& operator=(const GemmLog&) = delete;

  const std::vector<GemmShape>& shapes() const { return shapes_; }

  // Called by Mlp for each product; a no-op unless a log is alive.
  static void note(GemmShape::Kind kind, long out, long in, long batch) {
    if (active_ == nullptr) return;
    active_->shapes_.push_back({kind, static_cast<int>(out), static_cast<int>(in), static_cast<int>(batch)});
  }

 private:
  static GemmLog* active_;
  std::vector<GemmShape> shapes_;
};

double total_flops(const std::vector<GemmShape>& gemms);

}  // namespace rapid
