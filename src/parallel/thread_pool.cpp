#include "parallel/thread_pool.h"

#include <algorithm>
#include <atomic>

namespace raps {

ThreadPool::ThreadPool(int threads) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    workers_.reserve(static_cast<size_t>(threads - 1));
    try {
        for (int t = 1; t < threads; ++t) workers_.emplace_back([this] { work(); });
    } catch (...) {
        // A thread that cannot start (no memory for its state, no thread resources) leaves the
        // work to those that did: the output does not depend on their number. Letting the
        // exception out would destroy the started workers unjoined, which calls std::terminate
        // (found by failing each allocation in turn: tests/test_alloc_failures.c).
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& worker : workers_) worker.join();
}

int ThreadPool::threads_used() {
    std::lock_guard<std::mutex> lock(mutex_);
    return workers_that_worked_ + 1;
}

void ThreadPool::take_blocks(std::unique_lock<std::mutex>& lock, bool* worked) {
    while (next_block_ < blocks_) {
        const int64_t block = next_block_++;
        if (worked && !*worked) {
            *worked = true;
            ++workers_that_worked_;
        }
        const std::function<void(int64_t)>* task = task_;
        lock.unlock();
        try {
            (*task)(block);
        } catch (...) {
            lock.lock();
            if (!error_) error_ = std::current_exception();
            lock.unlock();
        }
        lock.lock();
        if (++finished_blocks_ == blocks_) done_.notify_all();
    }
}

void ThreadPool::work() {
    uint64_t seen = 0;
    bool worked = false;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
        if (stopping_) return;
        seen = generation_;
        take_blocks(lock, &worked);
    }
}

void ThreadPool::run(int64_t blocks, const std::function<void(int64_t)>& task) {
    if (blocks <= 0) return;
    if (workers_.empty()) {
        for (int64_t b = 0; b < blocks; ++b) task(b);
        return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    task_ = &task;
    blocks_ = blocks;
    next_block_ = 0;
    finished_blocks_ = 0;
    error_ = nullptr;
    ++generation_;
    wake_.notify_all();
    take_blocks(lock, nullptr);
    done_.wait(lock, [&] { return finished_blocks_ == blocks_; });
    task_ = nullptr;
    blocks_ = 0;
    next_block_ = 0;
    std::exception_ptr error = error_;
    error_ = nullptr;
    lock.unlock();
    if (error) std::rethrow_exception(error);
}

void parallel_for_each(ThreadPool& pool, size_t count, const std::function<void(size_t)>& body) {
    std::atomic<bool> failed{false};
    pool.run(static_cast<int64_t>(count), [&](int64_t i) {
        if (failed.load()) return;
        try {
            body(static_cast<size_t>(i));
        } catch (...) {
            failed.store(true);
            throw;
        }
    });
}

int choose_thread_count(int requested, int64_t items, int64_t per_thread) {
    int threads = requested > 0
                      ? requested
                      : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int64_t useful = std::max<int64_t>(1, items / std::max<int64_t>(1, per_thread));
    return static_cast<int>(std::max<int64_t>(1, std::min<int64_t>(threads, useful)));
}

}  // namespace raps
