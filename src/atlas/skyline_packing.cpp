#include "atlas/skyline_packing.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

namespace raps {

// The placed charts' cells as bit rows of a strip, growing upwards as needed.
class Occupancy {
    static constexpr int32_t kReservedRows = 4096;

  public:
    // Room for as many rows as the strip is wide is reserved (up to kReservedRows): layouts
    // grow to about a square, and growing the rows a chart at a time moved them again and
    // again (a tenth of packing a small mesh's atlas).
    explicit Occupancy(int32_t strip) : strip_(strip), words_((strip + 63) / 64 + 1) {
        const size_t rows = static_cast<size_t>(std::min(strip, kReservedRows));
        cells_.reserve(rows * words_);
        longest_free_.reserve(rows);
        runs_at_.reserve(rows);
        runs_state_.reserve(rows);
    }
    // A copy keeps the cells, not the measured runs: the repaired orders copy a layout for
    // each place they try (page_packing.cpp), and each copy measures the rows it visits.
    Occupancy(const Occupancy& other)
        : strip_(other.strip_),
          words_(other.words_),
          cells_(other.cells_),
          longest_free_(other.longest_free_),
          runs_at_(other.runs_at_.size()),
          runs_state_(other.runs_state_.size(), 0) {}
    Occupancy& operator=(const Occupancy&) = delete;

    // Whether the padded chart placed with its lower left cell at (x, y) meets an occupied
    // cell.
    bool collides(const Profile& p, int32_t x, int32_t y) const {
        const int32_t shift = x % 64, offset = x / 64;
        auto row_collides = [&](int32_t r) {
            const int32_t row = y + r;
            if (row >= rows()) return false;  // above everything placed
            const uint64_t* target = row_ptr(row) + offset;
            const uint64_t* source = p.padded_bits.data() + static_cast<size_t>(r) * p.words;
            // Only the row's words with cells: each lands on two words of the layout's row.
            for (int32_t w = p.word_span[2 * r], end = p.word_span[2 * r + 1]; w < end; ++w) {
                const uint64_t low = source[w] << shift;
                const uint64_t high = shift ? source[w] >> (64 - shift) : 0;
                if ((low & target[w]) | (high & target[w + 1])) return true;
            }
            return false;
        };

        // The middle row first: a chart's widest rows are near its middle, and a position in
        // a full region is rejected there at once (rounded charts barely touch their first
        // and last rows).
        const int32_t middle = p.height / 2, low = p.height / 4, high = 3 * p.height / 4;
        if (row_collides(middle)) return true;
        if (low != middle && row_collides(low)) return true;
        if (high != middle && high != low && row_collides(high)) return true;
        for (int32_t r = 0; r < p.height && y + r < rows(); ++r) {
            if (r != middle && r != low && r != high && row_collides(r)) return true;
        }
        return false;
    }

    void place(const Profile& p, int32_t x, int32_t y) {
        const int32_t needed = y + p.height;
        if (needed > rows()) {
            cells_.resize(static_cast<size_t>(needed) * words_, 0);
            longest_free_.resize(needed, -1);
            runs_at_.resize(needed);
            runs_state_.resize(needed, 0);
        }
        const int32_t shift = x % 64, offset = x / 64;
        for (int32_t r = 0; r < p.height; ++r) {
            uint64_t* target = row_ptr(y + r) + offset;
            const uint64_t* source = p.chart_bits.data() + static_cast<size_t>(r) * p.words;
            uint64_t carry = 0;
            for (int32_t w = 0; w < p.words; ++w) {
                target[w] |= (source[w] << shift) | carry;
                carry = shift ? source[w] >> (64 - shift) : 0;
            }
            target[p.words] |= carry;
            longest_free_[y + r] = -1;  // measured again when asked for
            runs_state_[y + r] = 0;
        }
    }

    int32_t rows() const { return static_cast<int32_t>(cells_.size() / words_); }

    // Calls fn(begin, end) for each run of free cells of a row at least `least` long, left to
    // right, until fn returns true; from `from` on (a run through it begins there).
    template <typename Fn>
    void for_each_free_run(int32_t row, int32_t least, Fn fn, int32_t from = 0) {
        if (row >= rows()) {
            if (strip_ - from >= least) fn(from, strip_);
            return;
        }
        // A row's first visit since it changed scans its bits from `from`, and may stop early;
        // a second one keeps its runs for the visits after (measured()).
        if (runs_state_[row] == 0) {
            runs_state_[row] = 1;
            const uint64_t* bits = row_ptr(row);
            for (int32_t begin = next_cell(bits, strip_, from, false); begin < strip_;) {
                const int32_t end = next_cell(bits, strip_, begin, true);
                if (end - begin >= least && fn(begin, end)) return;
                begin = next_cell(bits, strip_, end, false);
            }
            return;
        }
        const int32_t* runs = measured(row);
        const size_t count = 2 * static_cast<size_t>(runs_at_[row].count);
        // From the first run that ends past `from` (runs are ascending and disjoint).
        size_t low = 0, high = count / 2;
        while (low < high) {
            const size_t middle = (low + high) / 2;
            if (runs[2 * middle + 1] <= from)
                low = middle + 1;
            else
                high = middle;
        }
        for (size_t k = 2 * low; k < count; k += 2) {
            const int32_t begin = std::max(runs[k], from), end = runs[k + 1];
            if (end - begin >= least && fn(begin, end)) return;
        }
    }

    // The longest run of free cells in a row of the strip.
    int32_t longest_free(int32_t row) {
        if (row >= rows()) return strip_;
        if (longest_free_[row] < 0) longest_free_[row] = longest_run(row_ptr(row), strip_, false);
        return longest_free_[row];
    }

  private:
    uint64_t* row_ptr(int32_t row) { return cells_.data() + static_cast<size_t>(row) * words_; }
    const uint64_t* row_ptr(int32_t row) const {
        return cells_.data() + static_cast<size_t>(row) * words_;
    }

    // A row's free runs as (begin, end) pairs, measured once after the row last changed: a
    // chart's hole search visits the same rows' runs at every height and sample row it tries,
    // and scanning their bits each time was a quarter of packing 800 charts of a noisy scan
    // (raps-bench-atlas --noise 0.2 --subdivide 2 --mesh lion.off). They are appended to one
    // pool, dropped whole once stale rows fill it (per-row vectors cost more in allocations
    // than they saved on a layout of 30 charts).
    const int32_t* measured(int32_t row) {
        if (runs_state_[row] == 2) return run_pool_.data() + runs_at_[row].offset;
        if (run_pool_.size() > kRunPoolEntries) {
            run_pool_.clear();
            for (char& state : runs_state_) state = state == 2 ? 1 : state;
        }
        const size_t offset = run_pool_.size();
        const uint64_t* bits = row_ptr(row);
        for (int32_t begin = next_cell(bits, strip_, 0, false); begin < strip_;) {
            const int32_t end = next_cell(bits, strip_, begin, true);
            run_pool_.push_back(begin);
            run_pool_.push_back(end);
            begin = next_cell(bits, strip_, end, false);
        }
        runs_at_[row] = {offset, static_cast<int32_t>((run_pool_.size() - offset) / 2)};
        runs_state_[row] = 2;
        return run_pool_.data() + offset;
    }

    static constexpr size_t kRunPoolEntries = size_t(1) << 20;
    struct Runs {
        size_t offset = 0;
        int32_t count = 0;
    };

    int32_t strip_, words_;
    std::vector<uint64_t> cells_;
    std::vector<int32_t> longest_free_;  // per row, -1 until measured
    std::vector<int32_t> run_pool_;
    std::vector<Runs> runs_at_;     // per row, in run_pool_ where runs_state_ is 2
    std::vector<char> runs_state_;  // per row: 0 not visited since it changed, 1 once, 2 kept
};

namespace {

// The skyline search's inner loops and their caller: a quarter of cheburashka's atlas cycles,
// three quarters of suzanne's (50 charts, perf). The loops are integer arithmetic, exact in any
// instruction set, so they are also built for AVX2 (where its 32-bit max and widening sums are
// single instructions) and the variant the processor runs is picked once: the layouts stay the same
// on every processor. (Picked by hand, not by target_clones: its load-time resolvers crash under
// ThreadSanitizer.)
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RAPS_SKYLINE_AVX2 1
#endif

// The row a chart with resting rows `rest` comes to rest on over the skyline `sky`, or any row
// at or above `limit` once it is clear the row reaches it: the caller rejects such positions
// anyway, and most positions of a search are rejected within their first columns.
inline __attribute__((always_inline)) int32_t resting_row_loop(const int32_t* sky,
                                                               const int32_t* rest, int32_t width,
                                                               int32_t limit) {
    constexpr int32_t kChunk = 64;
    int32_t y = 0;
    for (int32_t begin = 0; begin < width && y < limit; begin += kChunk) {
        const int32_t end = std::min(width, begin + kChunk);
        for (int32_t i = begin; i < end; ++i) y = std::max(y, sky[i] - rest[i]);
    }
    return y;
}

// The skyline's height summed over the columns a chart occupies (occupied[i] is 0 or 1).
inline __attribute__((always_inline)) int64_t skyline_under_loop(const int32_t* sky,
                                                                 const int32_t* occupied,
                                                                 int32_t width) {
    int64_t under = 0;
    for (int32_t i = 0; i < width; ++i) under += occupied[i] * sky[i];
    return under;
}

// The probe columns' lower bound of the resting row at `count` consecutive positions: out[k]
// for the chart's left column at k. One pass per probe
// over the skyline, where position by position the probes were most of the packing of
// thousands of small charts.
inline __attribute__((always_inline)) void probe_bounds_loop(const int32_t* sky,
                                                             const int32_t* rest,
                                                             const int32_t* probes,
                                                             int32_t probe_count, int32_t count,
                                                             int32_t* out) {
    for (int32_t k = 0; k < count; ++k) out[k] = 0;
    for (int32_t j = 0; j < probe_count; ++j) {
        const int32_t* column = sky + probes[j];
        const int32_t below = rest[probes[j]];
        for (int32_t k = 0; k < count; ++k) out[k] = std::max(out[k], column[k] - below);
    }
}

int32_t resting_row_baseline(const int32_t* sky, const int32_t* rest, int32_t width,
                             int32_t limit) {
    return resting_row_loop(sky, rest, width, limit);
}
int64_t skyline_under_baseline(const int32_t* sky, const int32_t* occupied, int32_t width) {
    return skyline_under_loop(sky, occupied, width);
}
void probe_bounds_baseline(const int32_t* sky, const int32_t* rest, const int32_t* probes,
                           int32_t probe_count, int32_t count, int32_t* out) {
    probe_bounds_loop(sky, rest, probes, probe_count, count, out);
}
#ifdef RAPS_SKYLINE_AVX2
__attribute__((target("avx2"))) int32_t resting_row_avx2(const int32_t* sky, const int32_t* rest,
                                                         int32_t width, int32_t limit) {
    return resting_row_loop(sky, rest, width, limit);
}
__attribute__((target("avx2"))) int64_t skyline_under_avx2(const int32_t* sky,
                                                           const int32_t* occupied, int32_t width) {
    return skyline_under_loop(sky, occupied, width);
}
__attribute__((target("avx2"))) void probe_bounds_avx2(const int32_t* sky, const int32_t* rest,
                                                       const int32_t* probes, int32_t probe_count,
                                                       int32_t count, int32_t* out) {
    probe_bounds_loop(sky, rest, probes, probe_count, count, out);
}
#endif

SkylineKernels skyline_kernels() {
#ifdef RAPS_SKYLINE_AVX2
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return {resting_row_avx2, skyline_under_avx2, probe_bounds_avx2};
#endif
    return {resting_row_baseline, skyline_under_baseline, probe_bounds_baseline};
}

}  // namespace

// Positions one layout's hole searches test in all, at most. Without a bound the search costs
// the layout's free area per chart: 5,000 separate quads (foliage cards, a triangle soup) tested
// 269 million positions and 20,000 took minutes, where the ten-mesh scene of issue 23 tests
// 431,000 over all its layouts. Charts placed after the budget is spent keep the skyline's place.
constexpr int64_t kHoleTestsPerLayout = 2000000;

SkylineStrip::SkylineStrip(int32_t strip_cells, bool waste, bool holes, int turns)
    : strip(strip_cells),
      count_waste(waste),
      fill_holes(holes),
      turn_limit(turns),
      skyline_(static_cast<size_t>(strip_cells), 0),
      occupancy_(std::make_unique<Occupancy>(strip_cells)),
      kernels_(skyline_kernels()),
      bounds_(static_cast<size_t>(strip_cells)),
      skyline_sum_(waste ? static_cast<size_t>(strip_cells) + 1 : 0, 0),
      hole_tests_left_(kHoleTestsPerLayout) {}

SkylineStrip::~SkylineStrip() = default;
SkylineStrip::SkylineStrip(const SkylineStrip& other)
    : strip(other.strip),
      count_waste(other.count_waste),
      fill_holes(other.fill_holes),
      turn_limit(other.turn_limit),
      width(other.width),
      height(other.height),
      skyline_(other.skyline_),
      occupancy_(std::make_unique<Occupancy>(*other.occupancy_)),
      kernels_(other.kernels_),
      bounds_(other.bounds_),
      skyline_sum_(other.skyline_sum_),
      hole_tests_left_(other.hole_tests_left_) {}

bool SkylineStrip::find(const PreparedChart& chart, Placement& place) {
    // The state under the names the search had when it was one function, so that its lines
    // (and the layouts they make) stayed as they were.
    const std::vector<int32_t>& skyline = skyline_;
    const SkylineKernels& kernels = kernels_;
    std::vector<int32_t>& bounds = bounds_;
    const std::vector<int64_t>& skyline_sum = skyline_sum_;
    auto rest_height = [&](const Profile& p, int32_t x, int32_t limit) {
        return kernels.resting_row(skyline.data() + x, p.resting_bottom.data(), p.width, limit);
    };
    auto rest_height_at_least = [&](const Profile& p, int32_t x) {
        int32_t y;
        probe_bounds_loop(skyline.data() + x, p.resting_bottom.data(), p.probe_columns.data(),
                          static_cast<int32_t>(p.probe_columns.size()), 1, &y);
        return y;
    };
    // Lowest top first; or, with count_waste, the texels left empty under the chart plus the
    // area up to its top, which favours placements that fit the skyline's dips.
    auto score_of = [&](const Profile& p, int32_t x, int32_t y) -> int64_t {
        const int64_t top = static_cast<int64_t>(y) + p.height;
        if (!count_waste) return top * (int64_t(strip) + 1) + x;
        // Sum over occupied columns of y + bottom - skyline.
        const int64_t under =
            p.occupied_count == p.occupied_end - p.occupied_begin
                ? skyline_sum[x + p.occupied_end] - skyline_sum[x + p.occupied_begin]
                : kernels.skyline_under(skyline.data() + x, p.occupied.data(), p.width);
        const int64_t waste = p.occupied_count * y + p.occupied_bottom_sum - under;
        return (waste + top * p.width) * (int64_t(strip) + 1) + x;
    };
    // A lower bound of score_of(p, x, rest_height(p, x)): both rules grow with y, and the
    // waste is never negative. Positions whose bound does not beat the best so far are
    // skipped without the full rest height; the layout is the same.
    auto score_from_bound = [&](const Profile& p, int32_t x, int32_t bound) -> int64_t {
        const int64_t top = static_cast<int64_t>(bound) + p.height;
        return (count_waste ? top * p.width : top) * (int64_t(strip) + 1) + x;
    };
    auto score_at_least = [&](const Profile& p, int32_t x) -> int64_t {
        return score_from_bound(p, x, rest_height_at_least(p, x));
    };
    // The lowest resting row at x whose score, by the same bound, is no better than `score`:
    // the full rest height may stop once it gets there.
    auto row_limit = [&](const Profile& p, int32_t x, int64_t score) -> int32_t {
        if (score == std::numeric_limits<int64_t>::max())
            return std::numeric_limits<int32_t>::max();
        const int64_t per_row = (int64_t(strip) + 1) * (count_waste ? p.width : 1);
        const int64_t top = (score - x + per_row - 1) / per_row;  // ceil; score > x here
        return static_cast<int32_t>(
            std::clamp<int64_t>(top - p.height, 0, std::numeric_limits<int32_t>::max()));
    };
    int64_t best_score = std::numeric_limits<int64_t>::max();
    int32_t best_x = -1, best_y = 0;
    int best_q = 0;
    for (int q = 0; q < std::min(chart.turns, turn_limit); ++q) {
        const Profile& p = chart.profiles[q];
        if (p.width > strip) continue;
        const int32_t last = strip - p.width;
        const int32_t step = p.width < kNarrowChart ? 1 : p.width / 8;
        // The score at x and its resting row when it may beat `than`, given a lower bound
        // of the score; otherwise the largest score, which beats nothing.
        auto score_below = [&](int32_t x, int64_t at_least,
                               int64_t than) -> std::pair<int64_t, int32_t> {
            constexpr int64_t kNone = std::numeric_limits<int64_t>::max();
            if (at_least >= than) return {kNone, 0};
            const int32_t limit = row_limit(p, x, than);
            const int32_t y = rest_height(p, x, limit);
            if (y >= limit) return {kNone, 0};
            return {score_of(p, x, y), y};
        };
        auto consider = [&](int32_t x) {
            const auto [score, y] = score_below(x, score_at_least(p, x), best_score);
            if (score < best_score) {
                best_score = score;
                best_x = x;
                best_y = y;
                best_q = q;
            }
        };
        int32_t coarse_best = 0;
        int64_t coarse_score = std::numeric_limits<int64_t>::max();
        if (step == 1) {
            // row_limit falls with x, so a bound at or above its value just right of the best
            // so far rules a position out with one comparison.
            int32_t rest_limit = std::numeric_limits<int32_t>::max();
            // A narrow chart tries every position, and its probes give the resting row of
            // each (Profile::probe_columns): all in one pass, none searched again.
            kernels.probe_bounds(skyline.data(), p.resting_bottom.data(), p.probe_columns.data(),
                                 static_cast<int32_t>(p.probe_columns.size()), last + 1,
                                 bounds.data());
            for (int32_t x = 0; x <= last; ++x) {
                if (bounds[x] >= rest_limit) continue;
                const int64_t score = score_of(p, x, bounds[x]);
                if (score < coarse_score) {
                    coarse_score = score;
                    coarse_best = x;
                    rest_limit = row_limit(p, x + 1, coarse_score);  // for the x right of it
                }
            }
        } else {
            for (int32_t x = 0; x <= last; x += step) {
                const int64_t score = score_below(x, score_at_least(p, x), coarse_score).first;
                if (score < coarse_score) {
                    coarse_score = score;
                    coarse_best = x;
                }
            }
        }
        for (int32_t x = std::max(0, coarse_best - step + 1);
             x <= std::min(last, coarse_best + step - 1); ++x) {
            consider(x);
        }
        consider(last);
    }
    if (best_x < 0) return false;
    place.x = best_x;
    place.y = best_y;
    place.quarter = best_q;
    if (fill_holes) find_hole(chart, place);
    return true;
}

// Holes: a chart an eighth of the layout or smaller may fit lower, under an overhang the
// skyline cannot see. The free cells below its skyline position are scanned row by row in
// steps of a sixteenth of its height, each turn, and the first place found settles down and
// left cell by cell. In a row, only the columns where the chart's middle and sample rows each
// lie in one free run of the layout (run_positions) are tested, at steps of a 32nd of its width
// (at least 1/200 of the strip) and at each interval's end, so a hole a jagged chart fits only
// within a few columns is not stepped over (docs/square-atlas.md, "Holes searched by free
// runs": mean coverage of the shared meshes' squares 0.6520 -> 0.6532, held-out jittered and
// stretched meshes 0.678 -> 0.683; single meshes move either way by up to 0.03).
void SkylineStrip::find_hole(const PreparedChart& chart, Placement& place) {
    Occupancy& occupancy = *occupancy_;
    int64_t& tests = hole_tests_left_;
    std::vector<int32_t>& intervals = intervals_;
    for (int q = 0; q < std::min(chart.turns, turn_limit); ++q) {
        const Profile& p = chart.profiles[q];
        if (p.width > strip) continue;
        if (static_cast<int64_t>(p.width) * p.height * 8 > static_cast<int64_t>(width) * height)
            continue;  // larger charts rarely fit a hole (every chart: no better, 15% slower)
        const int32_t sx = std::max({1, p.width / 32, strip / 200});
        const int32_t sy = std::max({1, p.height / 16, height / 200});
        const int32_t best_top = place.y + chart.profiles[place.quarter].height;
        bool found = false;
        for (int32_t y = 0; !found && --tests > 0 && y + p.height < best_top; y += sy) {
            if (occupancy.longest_free(y + p.height / 2) < p.middle_run) continue;
            if (!room_in_samples(p, y)) continue;
            run_positions(p, y, intervals);
            for (size_t k = 0; k < intervals.size() && !found; k += 2) {
                for (int32_t x = intervals[k];; x = std::min(x + sx, intervals[k + 1])) {
                    if (--tests < 0) break;
                    if (!occupancy.collides(p, x, y)) {
                        settle(p, x, y);
                        place = {x, y, q};
                        found = true;
                        break;
                    }
                    if (x == intervals[k + 1]) break;
                }
            }
        }
    }
}

// Each free run a row's constraint visits counts as a test of the layout's budget, as each
// row find_hole looks at does, so that the budget bounds the work of thousands of charts.
void SkylineStrip::run_positions(const Profile& p, int32_t y, std::vector<int32_t>& out) {
    out.assign({0, strip - p.width});
    std::vector<int32_t>& next = run_scratch_;
    // Runs are visited from the first interval's column on: one cut there leaves the same
    // columns, and the visit stops past the last interval.
    auto constrain = [&](int32_t r, int32_t begin, int32_t length) {
        next.clear();
        size_t k = 0;
        auto runs = [&](int32_t free_begin, int32_t free_end) {
            --hole_tests_left_;
            const int32_t lo = free_begin - begin, hi = free_end - begin - length;
            while (k < out.size() && out[k + 1] < lo) k += 2;
            for (size_t j = k; j < out.size() && out[j] <= hi; j += 2) {
                const int32_t a = std::max(lo, out[j]), b = std::min(hi, out[j + 1]);
                if (a <= b) {
                    next.push_back(a);
                    next.push_back(b);
                }
            }
            return k >= out.size();  // every interval lies left of the runs still to come
        };
        occupancy_->for_each_free_run(y + r, length, runs, out.front() + begin);
        out.swap(next);
    };
    constrain(p.height / 2, p.middle_begin, p.middle_run);
    for (size_t k = 0; k < p.sample_runs.size() && !out.empty(); k += 3)
        constrain(p.sample_runs[k], p.sample_runs[k + 1], p.sample_runs[k + 2]);
}

bool SkylineStrip::room_in_samples(const Profile& p, int32_t y) {
    for (size_t k = 0; k < p.sample_runs.size(); k += 3) {
        if (occupancy_->longest_free(y + p.sample_runs[k]) < p.sample_runs[k + 2]) return false;
    }
    return true;
}

void SkylineStrip::settle(const Profile& p, int32_t& x, int32_t& y) const {
    const Occupancy& occupancy = *occupancy_;
    for (bool moved = true; moved;) {
        moved = false;
        if (y > 0 && !occupancy.collides(p, x, y - 1)) {
            --y;
            moved = true;
        } else if (x > 0 && !occupancy.collides(p, x - 1, y)) {
            --x;
            moved = true;
        }
    }
}

void SkylineStrip::commit(const PreparedChart& chart, const Placement& place) {
    std::vector<int32_t>& skyline = skyline_;
    std::vector<int64_t>& skyline_sum = skyline_sum_;
    const Profile& p = chart.profiles[place.quarter];
    occupancy_->place(p, place.x, place.y);
    for (int32_t i = 0; i < p.width; ++i) {
        if (p.top[i] >= 0)
            skyline[place.x + i] = std::max(skyline[place.x + i], place.y + p.top[i] + 1);
    }
    for (int32_t i = place.x; i < strip && count_waste; ++i)
        skyline_sum[i + 1] = skyline_sum[i] + skyline[i];
    width = std::max(width, place.x + p.width);
    height = std::max(height, place.y + p.height);
}

StripResult pack_strip(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                       int32_t strip, bool count_waste, bool fill_holes, int32_t max_side,
                       std::vector<Eigen::Vector2i>& at, std::vector<int>& quarter, int32_t& width,
                       int32_t& height, int turn_limit, const std::atomic<int64_t>* beaten_above) {
    SkylineStrip layout(strip, count_waste, fill_holes, turn_limit);
    width = height = 0;
    for (size_t c : order) {
        Placement place;
        if (!layout.find(prepared[c], place)) return StripResult::kTooLarge;
        layout.commit(prepared[c], place);
        at[c] = Eigen::Vector2i(place.x, place.y);
        quarter[c] = place.quarter;
        width = layout.width;
        height = layout.height;
        if (std::max(width, height) > max_side) return StripResult::kTooLarge;
        if (beaten_above &&
            layout_cost(width, height) > beaten_above->load(std::memory_order_relaxed))
            return StripResult::kBeaten;
    }
    return StripResult::kFits;
}

std::vector<std::vector<size_t>> size_orders(const std::vector<Eigen::Vector2d>& extents,
                                             bool further) {
    auto largest_first = [&](auto size_of) {
        std::vector<size_t> order(extents.size());
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return size_of(a) > size_of(b); });
        return order;
    };
    std::vector<std::vector<size_t>> orders = {
        largest_first([&](size_t c) { return extents[c].maxCoeff(); }),
        largest_first([&](size_t c) { return extents[c].x() * extents[c].y(); }),
        largest_first([&](size_t c) { return extents[c].minCoeff(); })};
    if (further) {
        orders.push_back(largest_first([&](size_t c) { return extents[c].x(); }));
        orders.push_back(largest_first([&](size_t c) { return extents[c].y(); }));
        orders.push_back(largest_first([&](size_t c) { return extents[c].sum(); }));
    }
    for (size_t k = orders.size(); k-- > 1;) {
        if (std::find(orders.begin(), orders.begin() + k, orders[k]) != orders.begin() + k)
            orders.erase(orders.begin() + k);
    }
    return orders;
}

}  // namespace raps
