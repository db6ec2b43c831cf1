// Large buffers filled in runs, with a progress call between two. A vector of tens of millions of
// entries (per directed edge, per nonzero of a system at millions of triangles) is mostly first
// touches of fresh pages: filled in one go it measured 20 to 120 ms of CPU at 3.3M triangles
// with no progress call, so a cancel waited that long. reserve() takes the memory without
// touching it; resize() within the capacity then touches one run at a time. The contents are
// those of one assign() or resize().
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/progress.h"

namespace raps {

// Entries per run: 2 MB of doubles, 512 fresh pages: about 5 ms where a page fault costs 10 us
// (measured in a loaded virtual machine), well under a millisecond on bare metal.
constexpr size_t kEntriesPerFillRun = size_t(1) << 18;

// v = count copies of value, `progress` told its fraction after each run.
template <typename T>
void assign_in_runs(std::vector<T>& v, size_t count, const T& value, const ProgressSpan& progress) {
    v.clear();
    v.reserve(count);
    while (v.size() < count) {
        const size_t next =
            count - v.size() > kEntriesPerFillRun ? v.size() + kEntriesPerFillRun : count;
        v.resize(next, value);
        if (progress.active()) progress.report(static_cast<double>(next) / count);
    }
}

// to = from, copied in runs as assign_in_runs fills (the sphere's points at 5M triangles are
// 68 MB, 30 to 60 ms copied in one go).
template <typename T>
void copy_in_runs(std::vector<T>& to, const std::vector<T>& from, const ProgressSpan& progress) {
    to.clear();
    to.reserve(from.size());
    while (to.size() < from.size()) {
        const size_t next = from.size() - to.size() > kEntriesPerFillRun
                                ? to.size() + kEntriesPerFillRun
                                : from.size();
        to.insert(to.end(), from.begin() + static_cast<std::ptrdiff_t>(to.size()),
                  from.begin() + static_cast<std::ptrdiff_t>(next));
        if (progress.active()) progress.report(static_cast<double>(next) / from.size());
    }
}

// A new vector of count copies of value, filled as assign_in_runs does.
template <typename T>
std::vector<T> filled_in_runs(size_t count, const T& value, const ProgressSpan& progress) {
    std::vector<T> v;
    assign_in_runs(v, count, value, progress);
    return v;
}

}  // namespace raps
