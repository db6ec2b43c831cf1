// What the dense kernels (dense_lu_kernel.inl, dense_cholesky_kernel.inl) share, included once
// by each of dense_kernels.cpp (baseline) and dense_kernels_avx2.cpp (AVX2).
//
// Both variants are this same source, plain loops: every element of the result gets the same
// operations in the same order in both (c = c - a * b, one rounding each, over the inner index
// in increasing order), whatever the tile shape or vector width the compiler uses. The library
// is compiled with -ffp-contract=off (no fused multiply-add) and never with -ffast-math-like
// flags (src/CMakeLists.txt), so the AVX2 variant is only wider, never differently rounded, and
// both give the same bits (docs/reproducibility.md). No Eigen and no std template here: the AVX2
// object must define nothing a baseline code path could link to (tests/check_avx2_isolation.cmake),
// and everything below has internal linkage.
#include <cmath>
#include <cstdint>

#include "solver/dense_kernels.h"

#if !defined(RAPS_KERNEL_TILE_ROWS) || !defined(RAPS_KERNEL_VECTOR_DOUBLES)
#error "RAPS_KERNEL_TILE_ROWS, RAPS_KERNEL_VECTOR_DOUBLES: set by the file including this one"
#endif

namespace raps {
namespace {

// Register tile of subtract_product: kTileRows x kTileCols accumulators. Only speed depends on
// it, never the bits (each element is computed by the same sequence of operations).
constexpr int32_t kTileRows = RAPS_KERNEL_TILE_ROWS;
constexpr int32_t kTileCols = 4;
// The tile's columns as vectors of the variant's width (GCC/clang vector extension: element-wise
// IEEE operations, the same as the scalar ones, and never fused with -ffp-contract=off).
typedef double Vector __attribute__((vector_size(RAPS_KERNEL_VECTOR_DOUBLES * sizeof(double))));
constexpr int32_t kVectorDoubles = RAPS_KERNEL_VECTOR_DOUBLES;
constexpr int32_t kTileVectors = kTileRows / kVectorDoubles;
static_assert(kTileRows % kVectorDoubles == 0, "a tile column is whole vectors");

inline int32_t smaller(int32_t a, int32_t b) {
    return a < b ? a : b;
}
inline double magnitude(double x) {
    return x < 0.0 ? -x : x;
}

// One element of subtract_product, in the order every path uses.
inline double subtract_dot(double c, const double* a, int64_t lda, const double* b, int64_t b_row,
                           int32_t depth) {
    for (int32_t p = 0; p < depth; ++p) c -= a[p * lda] * b[p * b_row];
    return c;
}

// C -= A * B, with C rows x cols (column stride ldc), A rows x depth (column stride lda) and
// B(p, j) = b[p * b_row + j * b_col] (b_row 1: B column-major; b_col 1: B is a transposed
// column-major block). With `lower`, only the elements on and below C's diagonal (row >= column)
// are read or written. Every element: c = ((c - a_0 b_0) - a_1 b_1) - ..., in that order.
void subtract_product(double* c, int64_t ldc, const double* a, int64_t lda, const double* b,
                      int64_t b_row, int64_t b_col, int32_t rows, int32_t cols, int32_t depth,
                      bool lower) {
    if (depth <= 0) return;
    for (int32_t j0 = 0; j0 < cols; j0 += kTileCols) {
        const int32_t jn = smaller(kTileCols, cols - j0);
        for (int32_t i0 = lower ? (j0 / kTileRows) * kTileRows : 0; i0 < rows; i0 += kTileRows) {
            const int32_t in = smaller(kTileRows, rows - i0);
            const bool full =
                in == kTileRows && jn == kTileCols && (!lower || i0 >= j0 + kTileCols - 1);
            if (!full) {
                for (int32_t jj = 0; jj < jn; ++jj) {
                    const int32_t j = j0 + jj;
                    for (int32_t ii = 0; ii < in; ++ii) {
                        const int32_t i = i0 + ii;
                        if (lower && i < j) continue;
                        double* target = c + i + static_cast<int64_t>(j) * ldc;
                        *target = subtract_dot(*target, a + i, lda, b + j * b_col, b_row, depth);
                    }
                }
                continue;
            }
            Vector acc[kTileCols][kTileVectors];
            for (int32_t jj = 0; jj < kTileCols; ++jj)
                for (int32_t v = 0; v < kTileVectors; ++v)
                    __builtin_memcpy(
                        &acc[jj][v],
                        c + i0 + v * kVectorDoubles + static_cast<int64_t>(j0 + jj) * ldc,
                        sizeof(Vector));
            for (int32_t p = 0; p < depth; ++p) {
                Vector column[kTileVectors];
                for (int32_t v = 0; v < kTileVectors; ++v)
                    __builtin_memcpy(&column[v], a + i0 + v * kVectorDoubles + p * lda,
                                     sizeof(Vector));
                const double* row = b + p * b_row + j0 * b_col;
                for (int32_t jj = 0; jj < kTileCols; ++jj) {
                    const double factor = row[jj * b_col];
                    for (int32_t v = 0; v < kTileVectors; ++v) acc[jj][v] -= column[v] * factor;
                }
            }
            for (int32_t jj = 0; jj < kTileCols; ++jj)
                for (int32_t v = 0; v < kTileVectors; ++v)
                    __builtin_memcpy(
                        c + i0 + v * kVectorDoubles + static_cast<int64_t>(j0 + jj) * ldc,
                        &acc[jj][v], sizeof(Vector));
        }
    }
}

// subtract_product in chunks of whole tile columns of about kMultiplyAddsPerChunk each, telling
// `progress` after each: every element gets the same operations in the same order whatever
// the chunks (see above), so the bits are those of one call, and a cancel waits for one chunk
// (a few milliseconds), not for a whole product (seconds for the largest fronts of a million
// triangles).
constexpr double kMultiplyAddsPerChunk = 4e6;

void subtract_product_in_chunks(double* c, int64_t ldc, const double* a, int64_t lda,
                                const double* b, int64_t b_row, int64_t b_col, int32_t rows,
                                int32_t cols, int32_t depth, bool lower,
                                const KernelProgress* progress) {
    const double per_column = static_cast<double>(rows) * (depth > 0 ? depth : 0);
    if (progress == nullptr || per_column * cols <= kMultiplyAddsPerChunk) {
        subtract_product(c, ldc, a, lda, b, b_row, b_col, rows, cols, depth, lower);
        if (progress != nullptr) progress->done(progress->context, per_column * cols);
        return;
    }
    int32_t width = static_cast<int32_t>(kMultiplyAddsPerChunk / per_column);
    width = width < kTileCols ? kTileCols : width / kTileCols * kTileCols;
    for (int32_t j0 = 0; j0 < cols; j0 += width) {
        const int32_t w = smaller(width, cols - j0);
        if (lower) {
            // Columns [j0, j0 + w) from row j0 down: the sub-block starts on the diagonal.
            subtract_product(c + j0 + static_cast<int64_t>(j0) * ldc, ldc, a + j0, lda,
                             b + j0 * b_col, b_row, b_col, rows - j0, w, depth, true);
        } else {
            subtract_product(c + static_cast<int64_t>(j0) * ldc, ldc, a, lda, b + j0 * b_col, b_row,
                             b_col, rows, w, depth, false);
        }
        progress->done(progress->context, per_column * w);
    }
}

// X = L^-1 X in place, L n x n unit lower triangular (column stride ldl), X n x cols (column
// stride ldx): forward substitution, column by column.
void solve_unit_lower(const double* l, int64_t ldl, int32_t n, double* x, int64_t ldx,
                      int32_t cols) {
    for (int32_t j = 0; j < cols; ++j) {
        double* column = x + static_cast<int64_t>(j) * ldx;
        for (int32_t p = 0; p < n; ++p) {
            const double factor = column[p];
            const double* l_column = l + static_cast<int64_t>(p) * ldl;
            for (int32_t i = p + 1; i < n; ++i) column[i] -= l_column[i] * factor;
        }
    }
}

// solve_unit_lower in chunks of columns of about kMultiplyAddsPerChunk each, telling `progress`
// after each: the columns are solved independently, so the bits are those of one call.
void solve_unit_lower_in_chunks(const double* l, int64_t ldl, int32_t n, double* x, int64_t ldx,
                                int32_t cols, const KernelProgress* progress) {
    const double per_column = 0.5 * static_cast<double>(n) * n;
    int32_t width = cols;
    if (progress != nullptr && per_column * cols > kMultiplyAddsPerChunk) {
        width = static_cast<int32_t>(kMultiplyAddsPerChunk / per_column);
        width = width < 1 ? 1 : width;
    }
    for (int32_t j0 = 0; j0 < cols; j0 += width) {
        const int32_t w = smaller(width, cols - j0);
        solve_unit_lower(l, ldl, n, x + j0 * ldx, ldx, w);
        if (progress != nullptr) progress->done(progress->context, per_column * w);
    }
}

}  // namespace
}  // namespace raps
