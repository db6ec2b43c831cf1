// Progress reporting and cancellation, passed down to every long-running algorithm as an
// argument (there is no global state). The callback returns false to cancel; report() then
// throws Error(kCancelled), which unwinds through RAII-owned memory only. Worker threads may
// report too: calls to the callback are serialised, so they never overlap.
#pragma once

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

class Progress {
  public:
    using Callback = std::function<bool(Phase, double)>;

    Progress() = default;
    explicit Progress(Callback callback) : callback_(std::move(callback)) {}

    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Reports that `fraction` (0..1) of `phase` is done; throws Error(kCancelled) on a stop.
    // Once cancelled, every later report (from any thread of the run) stops too, without
    // calling back again.
    void report(Phase phase, double fraction) const {
        if (!callback_) return;
        bool go_on;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            go_on = !cancelled_ && callback_(phase, fraction);
            cancelled_ = !go_on;
        }
        if (!go_on) throw Error(ErrorCode::kCancelled, "cancelled by the progress callback");
    }

  private:
    Callback callback_;
    mutable std::mutex mutex_;
    mutable bool cancelled_ = false;
};

}  // namespace raps
