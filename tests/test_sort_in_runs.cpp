// sort_in_runs (src/core/sort_in_runs.h), the sort that the sphere's equal-area start uses on
// millions of vertices: for a strict total order it gives std::sort's result element for
// element, whatever the size against its blocks, and it reports progress between blocks and
// merges, rising to 1. A test of an internal part, as test_portable_math is: through the C ABI
// only a changed sphere map (or a cancel that waited) would show a difference.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

// Before cmocka.h, whose fail() and skip() macros would rename the standard library's.
#include "core/sort_in_runs.h"
#include "support/split_mix.h"

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

namespace {

// Keys with many ties (a few hundred distinct values), ordered by key and then by index, as the
// sphere orders vertices by height: a strict total order.
std::vector<std::pair<double, int32_t>> keys(size_t n, Random& random) {
    std::vector<std::pair<double, int32_t>> v(n);
    for (size_t i = 0; i < n; ++i)
        v[i] = {static_cast<double>(static_cast<int>(random.uniform(0.0, 300.0))),
                static_cast<int32_t>(i)};
    return v;
}

bool less(const std::pair<double, int32_t>& x, const std::pair<double, int32_t>& y) {
    return x.first < y.first || (x.first == y.first && x.second < y.second);
}

void same_order_as_std_sort_at_every_size(void** state) {
    (void)state;
    Random random{7};
    const size_t run = raps::kSortRun;
    for (size_t n : {size_t(0), size_t(1), run - 1, run, run + 1, 3 * run + 17, 5 * run}) {
        std::vector<std::pair<double, int32_t>> expected = keys(n, random);
        std::vector<std::pair<double, int32_t>> got = expected;
        std::sort(expected.begin(), expected.end(), less);
        raps::sort_in_runs(got, less, raps::ProgressSpan());
        assert_true(got == expected);
    }
}

void reports_after_every_block_and_merge(void** state) {
    (void)state;
    Random random{11};
    const size_t n = 5 * raps::kSortRun + 3;  // 6 blocks; merges: 3 + 2 + 1
    std::vector<std::pair<double, int32_t>> v = keys(n, random);
    std::vector<double> fractions;
    const raps::Progress progress([&](raps::Phase, double fraction) {
        fractions.push_back(fraction);
        return true;
    });
    raps::sort_in_runs(v, less, raps::ProgressSpan(progress, raps::Phase::kAdapt));
    assert_int_equal(fractions.size(), 6 + 3 + 2 + 1);
    assert_true(std::is_sorted(fractions.begin(), fractions.end()));
    assert_true(fractions.back() == 1.0);
}

}  // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_order_as_std_sort_at_every_size),
        cmocka_unit_test(reports_after_every_block_and_merge),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
