// The matrix types of the network code: float32, column-major, one sample per column.
//
// Same seed, same bits on every machine that runs the binary (docs/design.md §Determinism) asks
// two things of Eigen beyond the compiler flags:
// - no EIGEN_FAST_MATH (CMakeLists.txt sets it to 0). With it, a float array's sqrt() and rsqrt()
//   refine the CPU's rsqrtps estimate, which is not the same table on Intel and AMD, so Adam's
//   and LayerNorm's results would depend on the CPU.
// - products planned for fixed cache sizes. Eigen reads the host's L1/L2/L3 at run time and
//   blocks a matrix product by them; another blocking sums a product's terms in another order
//   (layers of a few hundred units, large batches). core/mlp.cpp sets these before main().
#pragma once

#include <Eigen/Core>
#include <cstddef>

static_assert(EIGEN_FAST_MATH == 0,
              "rapid needs EIGEN_FAST_MATH=0 (CMakeLists.txt): Eigen's fast float sqrt depends on the CPU");

namespace rapid {

using Mat = Eigen::MatrixXf;
using Vec = Eigen::VectorXf;
using RowVec = Eigen::RowVectorXf;
using ConstMatRef = Eigen::Ref<const Mat>;
using VecRef = Eigen::Ref<Vec>;
using ConstVecRef = Eigen::Ref<const Vec>;

// The caches every process plans Eigen's products for, whatever it runs on: the smallest L1 and
// L2 among the x86 machines the harness has met (AMD EPYC: 32 KiB, 1 MiB; Intel Xeon: 48 KiB,
// 2 MiB). The L3 size only has to be non-zero for Eigen's heuristic.
inline constexpr std::ptrdiff_t kPlannedL1CacheBytes = 32 * 1024;
inline constexpr std::ptrdiff_t kPlannedL2CacheBytes = 1024 * 1024;
inline constexpr std::ptrdiff_t kPlannedL3CacheBytes = 32 * 1024 * 1024;

}  // namespace rapid
