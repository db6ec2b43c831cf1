// A pool of worker threads owned by one run (no global state), and a parallel for whose result
// never depends on the number of threads: work is cut into blocks of a fixed size, whatever the
// thread count, each block is computed by whichever thread takes it, and any reduction over
// blocks is combined afterwards in block order on the calling thread. So every floating-point
// operation, and its order, is the same for 1 thread or 16: output is bit-identical.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace raps {

class ThreadPool {
  public:
    // threads: the number of threads that work, the caller's included (1: no workers; 0: one
    // per hardware thread). Fewer work when the system cannot start them all.
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int size() const { return static_cast<int>(workers_.size()) + 1; }
    // The threads that have computed at least one block so far, the caller's included (1 until
    // a worker takes one): what the work was really shared among, which size() only allows.
    int threads_used();

    // Calls task(block) once for every block in [0, blocks), on the calling thread and the
    // workers, and returns when all are done. An exception thrown by a task is rethrown here
    // (the first one; the other blocks still run).
    void run(int64_t blocks, const std::function<void(int64_t)>& task);

  private:
    void work();
    // `worked`: whether this worker has taken a block yet (nullptr for the calling thread).
    void take_blocks(std::unique_lock<std::mutex>& lock, bool* worked);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(int64_t)>* task_ = nullptr;
    int64_t blocks_ = 0, next_block_ = 0, finished_blocks_ = 0;
    uint64_t generation_ = 0;
    int workers_that_worked_ = 0;
    bool stopping_ = false;
    std::exception_ptr error_;
};

// Items per block of parallel_for: fixed, so that results do not depend on the thread count.
constexpr int64_t kParallelBlock = 2048;

// body(begin, end) for consecutive ranges covering [0, count), in blocks of kParallelBlock.
template <typename Body>
void parallel_for(ThreadPool& pool, int64_t count, Body&& body) {
    const int64_t blocks = (count + kParallelBlock - 1) / kParallelBlock;
    if (blocks <= 1 || pool.size() == 1) {
        for (int64_t b = 0; b < blocks; ++b) {
            body(b * kParallelBlock, std::min(count, (b + 1) * kParallelBlock));
        }
        return;
    }
    pool.run(blocks, [&](int64_t b) {
        body(b * kParallelBlock, std::min(count, (b + 1) * kParallelBlock));
    });
}

// body(i) once for every i in [0, count), one item per block: items are taken in index order by
// whichever thread is free, so a caller that lists its largest work first keeps the threads
// busy to the end. Each body must write only its own slot, so results do not depend on the
// thread count or the schedule. Once a body has thrown, the items not yet started are skipped
// and the first exception is rethrown here.
void parallel_for_each(ThreadPool& pool, size_t count, const std::function<void(size_t)>& body);

// Sum over [0, count) of term(begin, end) per block, added in block order: the same bits for any
// thread count. T needs T() as zero and operator+=.
template <typename T, typename Term>
T parallel_sum(ThreadPool& pool, int64_t count, Term&& term) {
    const int64_t blocks = (count + kParallelBlock - 1) / kParallelBlock;
    std::vector<T> partial(static_cast<size_t>(blocks));
    parallel_for(pool, count, [&](int64_t begin, int64_t end) {
        partial[static_cast<size_t>(begin / kParallelBlock)] = term(begin, end);
    });
    T total{};
    for (const T& p : partial) total += p;
    return total;
}

// The thread count a run uses: `requested` (0: the hardware's), at most one per `per_thread`
// items of work and at least 1. The output does not depend on it.
int choose_thread_count(int requested, int64_t items, int64_t per_thread);

}  // namespace raps
