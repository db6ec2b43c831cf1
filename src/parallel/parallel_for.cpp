#include "parallel/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace raps {

int resolve_thread_count(int threads) {
    if (threads > 0) return threads;
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware ? static_cast<int>(hardware) : 1;
}

void parallel_for(int threads, size_t count, const std::function<void(size_t)>& body) {
    const size_t workers =
        std::min<size_t>(static_cast<size_t>(resolve_thread_count(threads)), count);
    if (workers <= 1) {
        for (size_t i = 0; i < count; ++i) body(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr first_error;
    std::mutex error_mutex;
    auto work = [&] {
        for (;;) {
            const size_t i = next.fetch_add(1);
            if (i >= count || failed.load()) return;
            try {
                body(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(error_mutex);
                if (!first_error) first_error = std::current_exception();
                failed.store(true);
            }
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    try {
        for (size_t t = 1; t < workers; ++t) pool.emplace_back(work);
    } catch (...) {
        // Could not start a thread (resources): the ones started and this one do the work.
    }
    work();
    for (std::thread& thread : pool) thread.join();
    if (first_error) std::rethrow_exception(first_error);
}

}  // namespace raps
