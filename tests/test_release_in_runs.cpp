// release_in_runs (src/core/release_in_runs.h), how the sphere and the solver free buffers of
// hundreds of megabytes at millions of triangles: the pages are given back one run at a time,
// with a progress call after each, so that a cancel never waits for one large free. A test of
// an internal part, as test_sort_in_runs is: through the C ABI only a cancel that waited would
// show a difference, and the tests count work, never time.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

// Before cmocka.h, whose fail() and skip() macros would rename the standard library's.
#include "core/release_in_runs.h"

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

namespace {

constexpr size_t kRun = size_t(1) << 20;

std::vector<double> progress_of(const std::function<void(const raps::ProgressSpan&)>& work) {
    std::vector<double> fractions;
    const raps::Progress progress([&](raps::Phase, double fraction) {
        fractions.push_back(fraction);
        return true;
    });
    work(raps::ProgressSpan(progress, raps::Phase::kAdapt));
    return fractions;
}

void gives_pages_back_a_run_at_a_time(void** state) {
    (void)state;
    // Seven and a half runs of pages, every byte written, so that every page is resident.
    std::vector<unsigned char> buffer(15 * kRun / 2, 0xAB);
    const std::vector<double> fractions = progress_of([&](const raps::ProgressSpan& span) {
        raps::release_pages_in_runs(buffer.data(), buffer.size(), span, kRun);
    });
    // A call between two of the eight runs (the last one partial), rising.
    assert_int_equal(fractions.size(), 7);
    for (size_t i = 0; i < fractions.size(); ++i)
        assert_true(fractions[i] == static_cast<double>(i + 1) / 8.0);
#if defined(__linux__)
    // Given back: the whole pages inside the buffer read as zeros again (a private anonymous
    // page after MADV_DONTNEED); the bytes of the partial pages at its ends are kept.
    const uintptr_t first = reinterpret_cast<uintptr_t>(buffer.data());
    const uintptr_t page_begin = (first + 4095) & ~uintptr_t(4095);
    const uintptr_t page_end = (first + buffer.size()) & ~uintptr_t(4095);
    size_t zeros = 0;
    for (size_t i = 0; i < buffer.size(); ++i) {
        const uintptr_t at = first + i;
        if (at >= page_begin && at < page_end) {
            zeros += buffer[i] == 0;
        } else {
            assert_int_equal(buffer[i], 0xAB);
        }
    }
    assert_int_equal(zeros, page_end - page_begin);
#endif
}

void release_in_runs_frees_the_vector(void** state) {
    (void)state;
    std::vector<double> values(3 * kRun, 1.0);
    raps::release_in_runs(values, raps::ProgressSpan());
    assert_int_equal(values.size(), 0);
    assert_int_equal(values.capacity(), 0);
    std::vector<double> empty;
    const std::vector<double> fractions =
        progress_of([&](const raps::ProgressSpan& span) { raps::release_in_runs(empty, span); });
    assert_int_equal(fractions.size(), 0);
    assert_int_equal(empty.capacity(), 0);
}

}  // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gives_pages_back_a_run_at_a_time),
        cmocka_unit_test(release_in_runs_frees_the_vector),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
