// The AVX2 + FMA build of the dense kernels (compiled with -mavx2 -mfma; see dense_kernels.h).
// Its Eigen gets a namespace of its own: template instances compiled for AVX2 must never be
// picked by the linker for code that runs on processors without it.
#undef Eigen
#define Eigen raps_eigen_avx2

#include "solver/dense_kernels.h"

#include "solver/dense_kernels_common.inl"
#define RAPS_PARTIAL_LU partial_lu_avx2
#include "solver/dense_lu_kernel.inl"
#define RAPS_PARTIAL_CHOLESKY partial_cholesky_avx2
#include "solver/dense_cholesky_kernel.inl"
