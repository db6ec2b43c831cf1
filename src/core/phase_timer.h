// Times one phase of a run and reports its start and end to the progress callback.
#pragma once

#include <array>
#include <chrono>

#include "core/progress.h"

namespace raps {

using PhaseTimes = std::array<double, kPhaseCount>;  // milliseconds per Phase

class PhaseTimer {
  public:
    PhaseTimer(Phase phase, const Progress& progress, PhaseTimes& times)
        : phase_(phase),
          progress_(progress),
          times_(times),
          start_(std::chrono::steady_clock::now()) {
        progress_.start(phase_);
    }
    // The phase's progress, for the steps inside it.
    ProgressSpan span(double from = 0.0, double to = 1.0) const {
        return ProgressSpan(progress_, phase_, from, to);
    }
    // Reports the end of the phase (which may still cancel) and records its duration.
    void finish() {
        record();
        progress_.report(phase_, 1.0);
    }
    ~PhaseTimer() { record(); }
    PhaseTimer(const PhaseTimer&) = delete;
    PhaseTimer& operator=(const PhaseTimer&) = delete;

  private:
    void record() {
        if (recorded_) return;
        recorded_ = true;
        const auto elapsed = std::chrono::steady_clock::now() - start_;
        times_[static_cast<int>(phase_)] +=
            std::chrono::duration<double, std::milli>(elapsed).count();
    }

    Phase phase_;
    const Progress& progress_;
    PhaseTimes& times_;
    std::chrono::steady_clock::time_point start_;
    bool recorded_ = false;
};

}  // namespace raps
