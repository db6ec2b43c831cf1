// Dense partial LU of a multifrontal front, the kernel where the sparse factorization spends
// most of its time. Built twice from dense_lu_kernel.inl: for the baseline instruction set and
// for AVX2 + FMA; fastest_partial_lu() picks the variant the processor runs, once. The two
// variants round differently, so results are bit-identical for a given build on processors of
// the same kind, not across the two kinds.
#pragma once

#include <cstdint>

namespace raps {

// Partial LU without pivoting of the m x m column-major front F = [F11 F12; F21 F22], F11 k x k:
// F11 = L11 U11 (L11 unit lower), L21 = F21 U11^-1, U12 = L11^-1 F12, and F22 -= L21 U12.
// Returns false when a pivot is not larger than 1e-13 times pivot_scale[j].
using PartialLu = bool (*)(double* front, int32_t m, int32_t k, const double* pivot_scale);

bool partial_lu_baseline(double* front, int32_t m, int32_t k, const double* pivot_scale);
bool partial_lu_avx2(double* front, int32_t m, int32_t k, const double* pivot_scale);

PartialLu fastest_partial_lu();

}  // namespace raps
