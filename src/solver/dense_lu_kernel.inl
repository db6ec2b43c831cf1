// The dense partial LU, included after dense_kernels_common.inl by dense_kernels.cpp and
// dense_kernels_avx2.cpp with RAPS_PARTIAL_LU set to the variant's name.
namespace raps {
namespace {

// Unblocked LU of the columns [first, first + count) of the m-row front, rows from `first`:
// each pivot column updates the columns to its right up to `update_end` (exclusive).
bool unblocked_lu(double* front, int32_t m, int32_t first, int32_t count, int32_t update_end,
                  const double* pivot_scale) {
    for (int32_t j = first; j < first + count; ++j) {
        double* column = front + static_cast<int64_t>(j) * m;
        const double pivot = column[j];
        if (!(magnitude(pivot) > 1e-13 * pivot_scale[j])) return false;
        const double inverse = 1.0 / pivot;
        for (int32_t i = j + 1; i < m; ++i) column[i] *= inverse;
        for (int32_t c = j + 1; c < update_end; ++c) {
            double* target = front + static_cast<int64_t>(c) * m;
            const double factor = target[j];
            if (factor == 0.0) continue;
            for (int32_t i = j + 1; i < m; ++i) target[i] -= column[i] * factor;
        }
    }
    return true;
}

// Recursive LU of a column panel (Toledo 1997): factor the left half, update the right half
// with one triangular solve and one matrix product, factor the right half. Nearly all the work
// lands in matrix products, unlike a column-by-column loop.
bool recursive_lu(double* front, int32_t m, int32_t first, int32_t count, const double* pivot_scale,
                  WorkCounter& work) {
    constexpr int32_t kUnblocked = 8;
    if (count <= kUnblocked)
        return unblocked_lu(front, m, first, count, first + count, pivot_scale);
    const int32_t left = count / 2, right = count - left, mid = first + left;
    if (!recursive_lu(front, m, first, left, pivot_scale, work)) return false;
    // A12 = L11^-1 A12, then A22 -= L21 A12 (A22 and L21 from row mid to the front's end).
    double* a12 = front + first + static_cast<int64_t>(mid) * m;
    solve_unit_lower(front + first + static_cast<int64_t>(first) * m, m, left, a12, m, right, work);
    subtract_product(front + mid + static_cast<int64_t>(mid) * m, m,
                     front + mid + static_cast<int64_t>(first) * m, m, a12, 1, m, m - mid, right,
                     left, false, work);
    return recursive_lu(front, m, mid, right, pivot_scale, work);
}

}  // namespace

bool RAPS_PARTIAL_LU(double* front, int32_t m, int32_t k, const double* pivot_scale,
                     const KernelProgress* progress) {
    // Small fronts (m <= 64 covers nearly all of an atlas's chart-sized systems) column by
    // column, every pivot column updating all columns to its right, the Schur complement
    // included: the blocked path's triangular solves and matrix products cost more in set-up
    // than in arithmetic at these sizes.
    constexpr int32_t kSmallFront = 64;
    if (m <= kSmallFront) return unblocked_lu(front, m, 0, k, m, pivot_scale);
    WorkCounter work{progress, 0.0};
    if (!recursive_lu(front, m, 0, k, pivot_scale, work)) return false;
    const int32_t rest = m - k;
    if (rest == 0) {
        work.flush();
        return true;
    }
    // The Schur complement as one product of inner dimension k: U12 = L11^-1 F12, then
    // F22 -= L21 U12.
    double* u12 = front + static_cast<int64_t>(k) * m;
    solve_unit_lower(front, m, k, u12, m, rest, work);
    subtract_product(front + k + static_cast<int64_t>(k) * m, m, front + k, m, u12, 1, m, rest,
                     rest, k, false, work);
    work.flush();
    return true;
}

}  // namespace raps
