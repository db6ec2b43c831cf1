// Dense partial factorizations of a multifrontal front, the kernels where the sparse
// factorization spends most of its time. Built twice from dense_lu_kernel.inl and
// dense_cholesky_kernel.inl: for the baseline instruction set and for AVX2; the fastest_*
// functions pick the variant the processor runs, once (the environment variable
// RAPS_KERNELS=baseline forces the baseline one, for testing). Both variants do the same
// operations in the same order on every element, without fused multiply-add, so they return the
// same bits (dense_kernels_common.inl, docs/reproducibility.md).
#pragma once

#include <cstdint>

namespace raps {

// Told, inside a large front, of each piece of its work done (in multiply-adds, a few million
// at most each), so that the caller can report progress or cancel: done() may throw, which
// leaves the front half-factored. A plain function pointer: the AVX2 object must instantiate
// nothing (tests/check_avx2_isolation.cmake). NULL: nobody is told.
struct KernelProgress {
    void (*done)(void* context, double multiply_adds);
    void* context;
};

// Both eliminate the first k columns of the m x m column-major front F = [F11 F12; F21 F22],
// F11 k x k, and return false when a pivot is not larger than 1e-13 times pivot_scale[j].
using PartialFactorization = bool (*)(double* front, int32_t m, int32_t k,
                                      const double* pivot_scale, const KernelProgress* progress);

// LU without pivoting: F11 = L11 U11 (L11 unit lower), L21 = F21 U11^-1, U12 = L11^-1 F12, and
// F22 -= L21 U12.
bool partial_lu_baseline(double* front, int32_t m, int32_t k, const double* pivot_scale,
                         const KernelProgress* progress);
bool partial_lu_avx2(double* front, int32_t m, int32_t k, const double* pivot_scale,
                     const KernelProgress* progress);
PartialFactorization fastest_partial_lu();

// Cholesky of a symmetric front, reading and writing only its lower triangle (the upper one may
// hold anything): F11 = L11 L11^T, L21 = F21 L11^-T, and F22 -= L21 L21^T. Half the work of the
// LU; a pivot that is not positive (the matrix is not positive definite) also returns false.
bool partial_cholesky_baseline(double* front, int32_t m, int32_t k, const double* pivot_scale,
                               const KernelProgress* progress);
bool partial_cholesky_avx2(double* front, int32_t m, int32_t k, const double* pivot_scale,
                           const KernelProgress* progress);
PartialFactorization fastest_partial_cholesky();

}  // namespace raps
