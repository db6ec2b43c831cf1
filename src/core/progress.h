// Progress reporting and cancellation, passed down to every long-running algorithm as an
// argument (there is no global state). The callback returns false to cancel; report() then
// throws Error(kCancelled), which unwinds through RAII-owned memory only. Worker threads may
// report too: calls to the callback are serialised, so they never overlap.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>

#include "core/error.h"

namespace raps {

enum class Phase : int {
    kValidate = 0,
    kTopology = 1,
    kInitialMap = 2,
    kAdapt = 3,
    kMetrics = 4,
    kSegment = 5,
    kPack = 6,
};
constexpr int kPhaseCount = 7;

// A run's progress as a caller polls it (raps_progress_state): the run writes each report here,
// any thread reads it, and a cancel set here stops the run at its next report. It exists for
// callers whose callbacks are costly to enter from the run's worker threads: a Python callback
// called from a thread Python did not create took 40 to 90 us per call, five to nine times the
// library's own time on small meshes (docs/blender.md). The phase, fraction and count are read
// together under the lock, never a phase with another report's fraction.
class ProgressState {
  public:
    struct Reading {
        int32_t phase = -1;  // none reported yet
        double fraction = 0.0;
        int64_t reports = 0;
    };

    // Records a report; false once cancelled (the run then stops).
    bool record(Phase phase, double fraction) {
        std::lock_guard<std::mutex> lock(mutex_);
        reading_.phase = static_cast<int32_t>(phase);
        reading_.fraction = fraction;
        ++reading_.reports;
        return !cancelled_.load(std::memory_order_relaxed);
    }
    Reading read() const {
        std::lock_guard<std::mutex> lock(mutex_);
        return reading_;
    }
    void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
    void reset() {
        std::lock_guard<std::mutex> lock(mutex_);
        reading_ = Reading();
        cancelled_.store(false, std::memory_order_relaxed);
    }

  private:
    mutable std::mutex mutex_;
    Reading reading_;
    std::atomic<bool> cancelled_{false};
};

class Progress {
  public:
    using Callback = std::function<bool(Phase, double)>;

    Progress() = default;
    // Either or both: `state` (not owned) must outlive the run.
    explicit Progress(Callback callback, ProgressState* state = nullptr)
        : callback_(std::move(callback)), state_(state) {}

    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    bool active() const { return callback_ || state_; }

    // Reports the start of a pass through `phase` (fraction 0), from which its fractions rise.
    void start(Phase phase) const { report(phase, 0.0, true); }

    // Reports that `fraction` (0..1) of `phase` is done; throws Error(kCancelled) on a stop.
    // Once cancelled, every later report (from any thread of the run) stops too, without
    // calling back again. Worker threads report the fractions of their own pieces, which may
    // arrive out of order: the callback gets the largest fraction reported since the phase
    // started, so what it sees never falls.
    void report(Phase phase, double fraction) const { report(phase, fraction, false); }

  private:
    void report(Phase phase, double fraction, bool start) const {
        if (!active()) return;
        const char* stop = nullptr;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            double& last = last_fraction_[static_cast<int>(phase)];
            last = start ? 0.0 : std::max(last, std::min(fraction, 1.0));
            if (stopped_) {
                stop = stopped_;
            } else if (state_ && !state_->record(phase, last)) {
                stop = "cancelled through its progress state (raps_progress_state_cancel)";
            } else if (callback_ && !callback_(phase, last)) {
                stop = "cancelled by the progress callback";
            }
            stopped_ = stop;
        }
        if (stop) throw Error(ErrorCode::kCancelled, stop);
    }

    Callback callback_;
    ProgressState* state_ = nullptr;
    mutable std::mutex mutex_;
    mutable const char* stopped_ = nullptr;  // why the run stopped, once it has
    mutable std::array<double, kPhaseCount> last_fraction_{};
};

// Work between two progress calls: a loop reports every kItemsPerReport items (a triangle, a
// vertex, an edge: well under a microsecond each), so a cancel waits for a few milliseconds of
// work at most, and a call (a lock and the callback, well under a microsecond) costs nothing
// measurable against the work it follows.
constexpr int64_t kItemsPerReport = 8192;
static_assert((kItemsPerReport & (kItemsPerReport - 1)) == 0, "a power of two: a mask tests it");

// A share [from, to] of one phase's progress, handed to a step of it: the step reports its own
// fraction in [0, 1], which lands in that share of the run's Progress. Spans are passed down,
// never kept. A default span reports nothing (for callers outside a run: benchmarks of the
// internals).
class ProgressSpan {
  public:
    ProgressSpan() = default;
    ProgressSpan(const Progress& progress, Phase phase, double from = 0.0, double to = 1.0)
        : progress_(progress.active() ? &progress : nullptr), phase_(phase), from_(from), to_(to) {}

    void report(double fraction) const {
        if (progress_) progress_->report(phase_, from_ + (to_ - from_) * fraction);
    }
    // In a loop over `count` items, at item `i`: a report every kItemsPerReport items.
    void at(int64_t i, int64_t count) const {
        if ((i & (kItemsPerReport - 1)) == 0 && i > 0 && active())
            report(static_cast<double>(i) / static_cast<double>(count));
    }
    // The same for a loop that is the share [from, to] of this span (nothing computed between
    // reports: it runs at every item).
    void at(int64_t i, int64_t count, double from, double to) const {
        if ((i & (kItemsPerReport - 1)) == 0 && i > 0 && active())
            part(from, to).report(static_cast<double>(i) / static_cast<double>(count));
    }
    // body(begin, end) over [0, count) in runs of kItemsPerReport items, a report between two
    // runs: for the hottest loops, whose bodies then see no call they would have to keep their
    // values around (a report inside measured 2% more instructions on the disk's passes).
    template <typename Body>
    void in_runs(int64_t count, Body&& body) const {
        for (int64_t begin = 0; begin < count; begin += kItemsPerReport) {
            if (begin > 0 && active())
                report(static_cast<double>(begin) / static_cast<double>(count));
            body(begin, std::min(count, begin + kItemsPerReport));
        }
    }
    // The share [from, to] of this one, for a step of the step.
    ProgressSpan part(double from, double to) const {
        ProgressSpan span = *this;
        span.from_ = from_ + (to_ - from_) * from;
        span.to_ = from_ + (to_ - from_) * to;
        return span;
    }
    bool active() const { return progress_ != nullptr; }

  private:
    const Progress* progress_ = nullptr;
    Phase phase_ = Phase::kValidate;
    double from_ = 0.0, to_ = 1.0;
};

}  // namespace raps
