// minimum_degree_order (src/solver/minimum_degree.cpp), the order of every system up to
// 150,000 unknowns: Eigen's minimum degree routine on the lower triangle of the pattern. It must
// give the order Eigen's general overload gives on the whole pattern (the atlas's bits hang on
// it), and call the progress on both sides of the routine, which cannot report: at 5.8M
// triangles that routine is the atlas's longest wait. A test of an internal part, as
// test_sort_in_runs is: through the C ABI a changed order shows only as other rounding.
#include <algorithm>
#include <cstdint>
#include <vector>

// Before cmocka.h, whose fail() and skip() macros would rename the standard library's.
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include "solver/minimum_degree.h"

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

namespace {

// The pattern of a triangulated side x side grid (each cell cut by one diagonal) plus, apart,
// a path of `path` unknowns: two components, rows sorted, the diagonal present or not.
raps::SparsePattern grid_and_path(int side, int path, bool diagonal) {
    const int n = side * side + path;
    std::vector<std::vector<int32_t>> rows(static_cast<size_t>(n));
    auto link = [&](int a, int b) {
        rows[static_cast<size_t>(a)].push_back(b);
        rows[static_cast<size_t>(b)].push_back(a);
    };
    for (int i = 0; i < side; ++i) {
        for (int j = 0; j < side; ++j) {
            const int a = i * side + j;
            if (j + 1 < side) link(a, a + 1);
            if (i + 1 < side) link(a, a + side);
            if (i + 1 < side && j + 1 < side) link(a, a + side + 1);
        }
    }
    for (int k = side * side; k + 1 < n; ++k) link(k, k + 1);
    raps::SparsePattern pattern;
    pattern.size = n;
    for (int i = 0; i < n; ++i) {
        std::vector<int32_t>& row = rows[static_cast<size_t>(i)];
        if (diagonal) row.push_back(i);
        std::sort(row.begin(), row.end());
        pattern.columns.insert(pattern.columns.end(), row.begin(), row.end());
        pattern.row_offsets.push_back(static_cast<int32_t>(pattern.columns.size()));
    }
    return pattern;
}

std::vector<int32_t> general_overload_order(const raps::SparsePattern& pattern) {
    std::vector<Eigen::Triplet<double, int>> entries;
    for (int i = 0; i < pattern.size; ++i) {
        for (int32_t k = pattern.row_offsets[static_cast<size_t>(i)];
             k < pattern.row_offsets[static_cast<size_t>(i) + 1]; ++k)
            entries.emplace_back(pattern.columns[static_cast<size_t>(k)], i, 1.0);
    }
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> matrix(pattern.size, pattern.size);
    matrix.setFromTriplets(entries.begin(), entries.end());
    Eigen::AMDOrdering<int>::PermutationType permutation;
    Eigen::AMDOrdering<int>()(matrix, permutation);
    return std::vector<int32_t>(permutation.indices().data(),
                                permutation.indices().data() + pattern.size);
}

void orders_as_the_general_overload(void** state) {
    (void)state;
    for (const bool diagonal : {true, false}) {
        const raps::SparsePattern pattern = grid_and_path(40, 25, diagonal);
        const std::vector<int32_t> order = raps::minimum_degree_order(pattern);
        assert_true(order == general_overload_order(pattern));
        // A permutation of the unknowns.
        std::vector<int32_t> sorted = order;
        std::sort(sorted.begin(), sorted.end());
        for (int32_t k = 0; k < pattern.size; ++k) assert_int_equal(sorted[k], k);
    }
}

void reports_on_both_sides_of_the_routine(void** state) {
    (void)state;
    std::vector<double> fractions;
    const raps::Progress progress([&](raps::Phase, double fraction) {
        fractions.push_back(fraction);
        return true;
    });
    raps::minimum_degree_order(grid_and_path(30, 0, true),
                               raps::ProgressSpan(progress, raps::Phase::kInitialMap));
    assert_int_equal(fractions.size(), 2);
    assert_true(fractions[0] > 0.0 && fractions[0] < fractions[1] && fractions[1] < 1.0);
}

}  // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(orders_as_the_general_overload),
        cmocka_unit_test(reports_on_both_sides_of_the_routine),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
