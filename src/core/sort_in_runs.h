// A sort with a progress call between bounded steps: blocks of kSortRun elements sorted one at
// a time, then merged pairwise, a call after each block and each merge. For a strict total
// order (no two elements equivalent under `less`) the result is std::sort's, element for
// element. One std::sort of a few million elements is hundreds of milliseconds without a call.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/progress.h"

namespace raps {

constexpr size_t kSortRun = size_t(1) << 16;

template <typename T, typename Less>
void sort_in_runs(std::vector<T>& v, Less less, const ProgressSpan& progress) {
    const size_t n = v.size();
    size_t steps = 0, done = 0;
    for (size_t width = kSortRun; width < n; width *= 2) steps += (n + 2 * width - 1) / (2 * width);
    steps += (n + kSortRun - 1) / kSortRun;
    auto step_done = [&]() {
        if (progress.active()) progress.report(static_cast<double>(++done) / steps);
    };
    for (size_t begin = 0; begin < n; begin += kSortRun) {
        std::sort(v.begin() + begin, v.begin() + std::min(n, begin + kSortRun), less);
        step_done();
    }
    for (size_t width = kSortRun; width < n; width *= 2) {
        for (size_t begin = 0; begin < n; begin += 2 * width) {
            if (begin + width < n) {
                std::inplace_merge(v.begin() + begin, v.begin() + begin + width,
                                   v.begin() + std::min(n, begin + 2 * width), less);
            }
            step_done();
        }
    }
}

}  // namespace raps
