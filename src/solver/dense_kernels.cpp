#include "solver/dense_kernels.h"

#include "solver/dense_kernels_common.inl"
#define RAPS_PARTIAL_LU partial_lu_baseline
#include "solver/dense_lu_kernel.inl"
#define RAPS_PARTIAL_CHOLESKY partial_cholesky_baseline
#include "solver/dense_cholesky_kernel.inl"

namespace raps {

#if defined(RAPS_HAVE_AVX2_KERNEL)  // built with GCC or clang, which have the -mavx2 flag
namespace {

bool processor_has_avx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    return avx2;
}

}  // namespace
#endif

PartialFactorization fastest_partial_lu() {
#if defined(RAPS_HAVE_AVX2_KERNEL)
    if (processor_has_avx2()) return partial_lu_avx2;
#endif
    return partial_lu_baseline;
}

PartialFactorization fastest_partial_cholesky() {
#if defined(RAPS_HAVE_AVX2_KERNEL)
    if (processor_has_avx2()) return partial_cholesky_avx2;
#endif
    return partial_cholesky_baseline;
}

}  // namespace raps
