#include "solver/dense_lu.h"

#define RAPS_PARTIAL_LU partial_lu_baseline
#include "solver/dense_lu_kernel.inl"

namespace raps {

PartialLu fastest_partial_lu() {
#if defined(RAPS_HAVE_AVX2_KERNEL) && (defined(__GNUC__) || defined(__clang__))
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (avx2) return partial_lu_avx2;
#endif
    return partial_lu_baseline;
}

}  // namespace raps
