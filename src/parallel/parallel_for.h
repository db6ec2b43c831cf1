// Deterministic data parallelism over std::thread: body(i) runs once for every i in
// [0, count), on up to `threads` threads (the caller's included). Each call writes only its own
// slot of the output, so results do not depend on the thread count or the schedule. The first
// exception thrown by a body is rethrown on the calling thread after all threads stopped; the
// remaining indices are skipped once one has thrown.
#pragma once

#include <cstddef>
#include <functional>

namespace raps {

// 0 means every hardware thread.
int resolve_thread_count(int threads);

void parallel_for(int threads, size_t count, const std::function<void(size_t)>& body);

}  // namespace raps
