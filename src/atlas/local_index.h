// A chart's lookup from the ids of surface elements to its own positions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace raps {

// Where each surface element (triangle, vertex) sits in a chart's list of them, or -1. A chart
// of at least 1/16 of the surface gets an array over the whole surface, filled per chart;
// searching the chart's sorted list instead took 10% more CPU time on the ten-mesh scene
// (mispredicted branches of the searches against one memset). A smaller chart gets a hash table
// of its own size: merging maps thousands of small unions on a noisy scan, and an array over the
// surface for each made the memsets a sixth of the run (lion.off subdivided twice and jittered).
class LocalIndex {
  public:
    // ids[i]: the element at position i (the first position wins); `universe`: how many
    // elements the surface has.
    LocalIndex(const std::vector<int32_t>& ids, size_t universe) {
        if (16 * ids.size() >= universe) {
            position_.assign(universe, -1);
            for (size_t i = ids.size(); i-- > 0;) position_[ids[i]] = static_cast<int32_t>(i);
            return;
        }
        // Open addressing at a load of at most a half: a miss (a neighbour outside the chart)
        // ends at an empty slot within a few probes. At least two slots (a shift below 32).
        shift_ = 31;
        while (shift_ > 1 && (size_t(1) << (32 - shift_)) < 2 * ids.size()) --shift_;
        slots_.assign(size_t(1) << (32 - shift_), Slot{-1, -1});
        mask_ = slots_.size() - 1;
        for (size_t i = 0; i < ids.size(); ++i) {
            size_t s = slot_of(ids[i]);
            while (slots_[s].id >= 0 && slots_[s].id != ids[i]) s = (s + 1) & mask_;
            if (slots_[s].id < 0) slots_[s] = {ids[i], static_cast<int32_t>(i)};
        }
    }
    int32_t operator()(int32_t id) const {
        if (slots_.empty()) return position_[id];
        for (size_t s = slot_of(id);; s = (s + 1) & mask_) {
            if (slots_[s].id == id) return slots_[s].position;
            if (slots_[s].id < 0) return -1;
        }
    }

  private:
    struct Slot {
        int32_t id, position;
    };
    size_t slot_of(int32_t id) const {
        return static_cast<size_t>((static_cast<uint32_t>(id) * 0x9E3779B1u) >> shift_);
    }

    std::vector<int32_t> position_;  // the array over the surface
    std::vector<Slot> slots_;        // or the hash table
    int shift_ = 31;
    size_t mask_ = 0;
};

}  // namespace raps
