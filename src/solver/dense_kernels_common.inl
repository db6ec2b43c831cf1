// What the dense kernels (dense_lu_kernel.inl, dense_cholesky_kernel.inl) share, included once
// by each of dense_kernels.cpp and dense_kernels_avx2.cpp. Each variant is compiled with its own
// private copy of Eigen (the build renames Eigen's namespace per file), so the two never share
// a template instance.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace raps {
namespace {

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
using Block = Eigen::Map<Matrix, 0, Eigen::OuterStride<>>;

// Eigen sizes its matrix-product blocks from the processor's cache sizes, which changes the
// order of summation from one machine to another. Pinned to Eigen's own x86 defaults, the
// results depend only on the build, not on the machine's caches.
void pin_cache_sizes() {
    static const bool pinned = [] {
        Eigen::setCpuCacheSizes(32 * 1024, 256 * 1024, 2 * 1024 * 1024);
        return true;
    }();
    (void)pinned;
}

}  // namespace
}  // namespace raps
