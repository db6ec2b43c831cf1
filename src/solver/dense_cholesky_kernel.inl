// The dense partial Cholesky, included after dense_kernels_common.inl by dense_kernels.cpp and
// dense_kernels_avx2.cpp with RAPS_PARTIAL_CHOLESKY set to the variant's name. Only the lower
// triangle of the front is read or written.
namespace raps {
namespace {

// Unblocked Cholesky of the columns [first, first + count) of the m-row front: each pivot
// column updates the lower part of the columns to its right up to `update_end` (exclusive).
bool unblocked_cholesky(double* front, int32_t m, int32_t first, int32_t count, int32_t update_end,
                        const double* pivot_scale) {
    for (int32_t j = first; j < first + count; ++j) {
        double* column = front + static_cast<int64_t>(j) * m;
        // The same test as the LU's: for a symmetric matrix the squared Cholesky pivot is the
        // LU's pivot, so both give up on the same matrices, and on any that is not positive.
        const double pivot = column[j];
        if (!(pivot > 1e-13 * pivot_scale[j])) return false;
        const double root = std::sqrt(pivot);
        column[j] = root;
        const double inverse = 1.0 / root;
        for (int32_t i = j + 1; i < m; ++i) column[i] *= inverse;
        for (int32_t c = j + 1; c < update_end; ++c) {
            double* target = front + static_cast<int64_t>(c) * m;
            const double factor = column[c];
            if (factor == 0.0) continue;
            for (int32_t i = c; i < m; ++i) target[i] -= column[i] * factor;
        }
    }
    return true;
}

// Recursive Cholesky of a column panel, as recursive_lu: factor the left half, update the
// right half's lower part by one product, factor it.
bool recursive_cholesky(double* front, int32_t m, int32_t first, int32_t count,
                        const double* pivot_scale, WorkCounter& work) {
    constexpr int32_t kUnblocked = 8;
    if (count <= kUnblocked)
        return unblocked_cholesky(front, m, first, count, first + count, pivot_scale);
    const int32_t left = count / 2, right = count - left, mid = first + left;
    if (!recursive_cholesky(front, m, first, left, pivot_scale, work)) return false;
    // The lower part of columns [mid, mid + right), from row mid to the front's end, less
    // L L^T, L the factored left half's rows from mid on (L^T's top rows: the same block's
    // first `right` rows, read transposed).
    const double* l = front + mid + static_cast<int64_t>(first) * m;
    subtract_product(front + mid + static_cast<int64_t>(mid) * m, m, l, m, l, m, 1, m - mid, right,
                     left, true, work);
    return recursive_cholesky(front, m, mid, right, pivot_scale, work);
}

}  // namespace

bool RAPS_PARTIAL_CHOLESKY(double* front, int32_t m, int32_t k, const double* pivot_scale,
                           const KernelProgress* progress) {
    // Small fronts column by column, the Schur complement included (as in the LU).
    constexpr int32_t kSmallFront = 64;
    if (m <= kSmallFront) return unblocked_cholesky(front, m, 0, k, m, pivot_scale);
    WorkCounter work{progress, 0.0};
    if (!recursive_cholesky(front, m, 0, k, pivot_scale, work)) return false;
    const int32_t rest = m - k;
    if (rest == 0) {
        work.flush();
        return true;
    }
    // F22's lower triangle -= L21 L21^T.
    const double* l21 = front + k;
    subtract_product(front + k + static_cast<int64_t>(k) * m, m, l21, m, l21, m, 1, rest, rest, k,
                     true, work);
    work.flush();
    return true;
}

}  // namespace raps
