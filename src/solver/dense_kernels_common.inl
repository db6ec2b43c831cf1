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

// One kTileRows x kTileCols tile of C at c less the product of depth columns of A and rows of
// B, in registers: c -= a(., p) b(p, .) for p in increasing order.
inline void subtract_full_tile(double* c, int64_t ldc, const double* a, int64_t lda,
                               const double* b, int64_t b_row, int64_t b_col, int32_t depth) {
    Vector acc[kTileCols][kTileVectors];
    for (int32_t jj = 0; jj < kTileCols; ++jj)
        for (int32_t v = 0; v < kTileVectors; ++v)
            __builtin_memcpy(&acc[jj][v], c + v * kVectorDoubles + jj * ldc, sizeof(Vector));
    for (int32_t p = 0; p < depth; ++p) {
        Vector column[kTileVectors];
        for (int32_t v = 0; v < kTileVectors; ++v)
            __builtin_memcpy(&column[v], a + v * kVectorDoubles + p * lda, sizeof(Vector));
        const double* row = b + p * b_row;
        for (int32_t jj = 0; jj < kTileCols; ++jj) {
            const double factor = row[jj * b_col];
            for (int32_t v = 0; v < kTileVectors; ++v) acc[jj][v] -= column[v] * factor;
        }
    }
    for (int32_t jj = 0; jj < kTileCols; ++jj)
        for (int32_t v = 0; v < kTileVectors; ++v)
            __builtin_memcpy(c + v * kVectorDoubles + jj * ldc, &acc[jj][v], sizeof(Vector));
}

// A tile at the edge of C or across its diagonal (rows [i0, i0 + in), columns [j0, j0 + jn)),
// element by element; with `lower`, the elements above the diagonal are left alone.
inline void subtract_edge_tile(double* c, int64_t ldc, const double* a, int64_t lda,
                               const double* b, int64_t b_row, int64_t b_col, int32_t i0,
                               int32_t in, int32_t j0, int32_t jn, int32_t depth, bool lower) {
    for (int32_t jj = 0; jj < jn; ++jj) {
        const int32_t j = j0 + jj;
        for (int32_t ii = 0; ii < in; ++ii) {
            const int32_t i = i0 + ii;
            if (lower && i < j) continue;
            double* target = c + i + static_cast<int64_t>(j) * ldc;
            *target = subtract_dot(*target, a + i, lda, b + j * b_col, b_row, depth);
        }
    }
}

// Cache blocks of subtract_product: kDepthBlock columns of A by kRowBlock of its rows (256 KB,
// in the second-level cache) serve every tile column of C before the next block is read, where
// one sweep over all of A per tile column read the largest fronts' panels (tens of megabytes)
// from memory again for every four columns of C. Blocks split each element's sum into
// consecutive runs of p, in increasing order, so the operations and the bits stay the same.
constexpr int32_t kDepthBlock = 128;
constexpr int32_t kRowBlock = 256;
static_assert(kRowBlock % kTileRows == 0, "row blocks are whole tiles");

// How often the kernels tell their caller of the work done: a cancel waits for about this many
// multiply-adds (a few milliseconds), not for a whole product (seconds for the largest fronts of
// a million triangles). Reports fall between tiles, so they change no operation.
constexpr double kMultiplyAddsPerReport = 4e6;

// Counts multiply-adds and tells `progress` (may be NULL) about every kMultiplyAddsPerReport.
struct WorkCounter {
    const KernelProgress* progress;
    double pending;
    void add(double multiply_adds) {
        pending += multiply_adds;
        if (progress == nullptr || pending < kMultiplyAddsPerReport) return;
        const double done = pending;
        pending = 0;
        progress->done(progress->context, done);
    }
    void flush() {
        if (progress != nullptr && pending > 0) progress->done(progress->context, pending);
        pending = 0;
    }
};

// The tiles of columns [j0, j0 + jn) in rows [r0, row_end) of C less depth columns of A times
// rows of B (pointers already at the depth block's first column and row).
void subtract_tile_column(double* c, int64_t ldc, const double* a, int64_t lda, const double* b,
                          int64_t b_row, int64_t b_col, int32_t rows, int32_t r0, int32_t row_end,
                          int32_t j0, int32_t jn, int32_t depth, bool lower, WorkCounter& work) {
    const int32_t diagonal_tile = (j0 / kTileRows) * kTileRows;
    const int32_t i_begin = lower && diagonal_tile > r0 ? diagonal_tile : r0;
    for (int32_t i0 = i_begin; i0 < row_end; i0 += kTileRows) {
        const int32_t in = smaller(kTileRows, rows - i0);
        const bool full =
            in == kTileRows && jn == kTileCols && (!lower || i0 >= j0 + kTileCols - 1);
        if (full) {
            subtract_full_tile(c + i0 + static_cast<int64_t>(j0) * ldc, ldc, a + i0, lda,
                               b + j0 * b_col, b_row, b_col, depth);
        } else {
            subtract_edge_tile(c, ldc, a, lda, b, b_row, b_col, i0, in, j0, jn, depth, lower);
        }
    }
    if (i_begin < row_end) work.add(static_cast<double>(row_end - i_begin) * jn * depth);
}

// C -= A * B, with C rows x cols (column stride ldc), A rows x depth (column stride lda) and
// B(p, j) = b[p * b_row + j * b_col] (b_row 1: B column-major; b_col 1: B is a transposed
// column-major block). With `lower`, only the elements on and below C's diagonal (row >= column)
// are read or written. Every element: c = ((c - a_0 b_0) - a_1 b_1) - ..., in that order.
void subtract_product(double* c, int64_t ldc, const double* a, int64_t lda, const double* b,
                      int64_t b_row, int64_t b_col, int32_t rows, int32_t cols, int32_t depth,
                      bool lower, WorkCounter& work) {
    for (int32_t p0 = 0; p0 < depth; p0 += kDepthBlock) {
        const int32_t kc = smaller(kDepthBlock, depth - p0);
        const double* ap = a + p0 * lda;
        const double* bp = b + p0 * b_row;
        for (int32_t r0 = 0; r0 < rows; r0 += kRowBlock) {
            const int32_t row_end = smaller(r0 + kRowBlock, rows);
            for (int32_t j0 = 0; j0 < cols; j0 += kTileCols) {
                subtract_tile_column(c, ldc, ap, lda, bp, b_row, b_col, rows, r0, row_end, j0,
                                     smaller(kTileCols, cols - j0), kc, lower, work);
            }
        }
    }
}

// X = L^-1 X in place, L n x n unit lower triangular (column stride ldl), X n x cols (column
// stride ldx). Recursive (Toledo 1997, as the LU): X1 = L11^-1 X1, X2 -= L21 X1 (one product),
// X2 = L22^-1 X2, so nearly all the work is in subtract_product. Each element still gets
// x_i -= l_ip x_p for p = 0, 1, ..., i - 1 in that order (the product's p before the lower
// half's), the operations of forward substitution column by column, so the bits are its bits.
void solve_unit_lower(const double* l, int64_t ldl, int32_t n, double* x, int64_t ldx, int32_t cols,
                      WorkCounter& work) {
    constexpr int32_t kUnblocked = 16;
    if (n <= kUnblocked) {
        for (int32_t j = 0; j < cols; ++j) {
            double* column = x + static_cast<int64_t>(j) * ldx;
            for (int32_t p = 0; p < n; ++p) {
                const double factor = column[p];
                const double* l_column = l + static_cast<int64_t>(p) * ldl;
                for (int32_t i = p + 1; i < n; ++i) column[i] -= l_column[i] * factor;
            }
        }
        work.add(0.5 * static_cast<double>(n) * n * cols);
        return;
    }
    const int32_t top = n / 2;
    solve_unit_lower(l, ldl, top, x, ldx, cols, work);
    subtract_product(x + top, ldx, l + top, ldl, x, 1, ldx, n - top, cols, top, false, work);
    solve_unit_lower(l + top + static_cast<int64_t>(top) * ldl, ldl, n - top, x + top, ldx, cols,
                     work);
}

}  // namespace
}  // namespace raps
