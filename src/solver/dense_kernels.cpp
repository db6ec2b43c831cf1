#include "solver/dense_kernels.h"

#include <cstdlib>
#include <cstring>

// 4 rows x 4 columns of accumulators: 8 of the 16 xmm registers of baseline x86-64.
#define RAPS_KERNEL_TILE_ROWS 4
#define RAPS_KERNEL_VECTOR_DOUBLES 2
#include "solver/dense_kernels_common.inl"
#define RAPS_PARTIAL_LU partial_lu_baseline
#include "solver/dense_lu_kernel.inl"
#define RAPS_PARTIAL_CHOLESKY partial_cholesky_baseline
#include "solver/dense_cholesky_kernel.inl"

namespace raps {

#if defined(RAPS_HAVE_AVX2_KERNEL)  // built with GCC or clang, which have the -mavx2 flag
namespace {

// The AVX2 kernels when the processor has AVX2, unless the environment variable RAPS_KERNELS is
// "baseline" (for testing: both variants give the same bits, and tests/test_reproducibility.c
// checks it on one machine). Read once, on the first factorization.
bool use_avx2_kernels() {
    static const bool avx2 = [] {
        const char* forced = std::getenv("RAPS_KERNELS");
        if (forced != nullptr && std::strcmp(forced, "baseline") == 0) return false;
        return __builtin_cpu_supports("avx2") != 0;
    }();
    return avx2;
}

}  // namespace
#endif

PartialFactorization fastest_partial_lu() {
#if defined(RAPS_HAVE_AVX2_KERNEL)
    if (use_avx2_kernels()) return partial_lu_avx2;
#endif
    return partial_lu_baseline;
}

PartialFactorization fastest_partial_cholesky() {
#if defined(RAPS_HAVE_AVX2_KERNEL)
    if (use_avx2_kernels()) return partial_cholesky_avx2;
#endif
    return partial_cholesky_baseline;
}

}  // namespace raps
