// The AVX2 build of the dense kernels (compiled with -mavx2 and -ffp-contract=off; see
// dense_kernels.h): the same source as the baseline build, so the same bits, only wider vectors
// and a taller register tile. Nothing here may have external linkage but the two kernels: a
// shared template or inline function compiled for AVX2 could be the copy the linker keeps for
// every caller, which would then crash processors without AVX2 (tests/check_avx2_isolation.cmake
// checks the object in every build type).
#include "solver/dense_kernels.h"

// 8 rows x 4 columns of accumulators: 8 of the 16 ymm registers.
#define RAPS_KERNEL_TILE_ROWS 8
#define RAPS_KERNEL_VECTOR_DOUBLES 4
#include "solver/dense_kernels_common.inl"
#define RAPS_PARTIAL_LU partial_lu_avx2
#include "solver/dense_lu_kernel.inl"
#define RAPS_PARTIAL_CHOLESKY partial_cholesky_avx2
#include "solver/dense_cholesky_kernel.inl"
