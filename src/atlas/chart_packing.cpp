#include "atlas/chart_packing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.h"
#include "core/portable_math.h"

namespace raps {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
    std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    if (points.size() < 3) return points;
    std::vector<Eigen::Vector2d> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

// The rotation (as cos, sin) that aligns the smallest-area bounding box with the axes: one of
// the hull's edge directions.
Eigen::Vector2d best_rotation(const std::vector<Eigen::Vector2d>& uv) {
    const std::vector<Eigen::Vector2d> hull = convex_hull(uv);
    Eigen::Vector2d best(1, 0);
    double best_score = std::numeric_limits<double>::max();
    for (size_t i = 0; i < hull.size(); ++i) {
        Eigen::Vector2d edge = hull[(i + 1) % hull.size()] - hull[i];
        if (edge.norm() == 0) continue;
        edge.normalize();
        double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
        for (const Eigen::Vector2d& p : hull) {
            const double x = edge.x() * p.x() + edge.y() * p.y();
            const double y = -edge.y() * p.x() + edge.x() * p.y();
            lo_x = std::min(lo_x, x);
            hi_x = std::max(hi_x, x);
            lo_y = std::min(lo_y, y);
            hi_y = std::max(hi_y, y);
        }
        const double score = (hi_x - lo_x) * (hi_y - lo_y);
        if (score < best_score - 1e-12 * std::abs(best_score)) {
            best_score = score;
            best = edge;
        }
    }
    return best;
}

// A bit image: bit x of row y is cell (x, y).
struct BitImage {
    int32_t width = 0, height = 0, words = 0;
    std::vector<uint64_t> bits;
    void resize(int32_t w, int32_t h) {
        width = w;
        height = h;
        words = (w + 63) / 64;
        bits.assign(static_cast<size_t>(words) * h, 0);
    }
    uint64_t* row(int32_t y) { return bits.data() + static_cast<size_t>(y) * words; }
    const uint64_t* row(int32_t y) const { return bits.data() + static_cast<size_t>(y) * words; }
    // Cells x0..x1 of row y, a word at a time: rasterising is linear in rows, not in cells.
    void set_span(int32_t y, int32_t x0, int32_t x1) {
        if (x0 > x1) return;
        uint64_t* cells = row(y);
        const int32_t first = x0 / 64, last = x1 / 64;
        const uint64_t from_x0 = ~uint64_t(0) << (x0 % 64);
        const uint64_t to_x1 = ~uint64_t(0) >> (63 - x1 % 64);
        if (first == last) {
            cells[first] |= from_x0 & to_x1;
            return;
        }
        cells[first] |= from_x0;
        for (int32_t w = first + 1; w < last; ++w) cells[w] = ~uint64_t(0);
        cells[last] |= to_x1;
    }
};

// floor(x) for the raster's coordinates (well inside int32_t): std::floor is a library call
// on baseline x86-64, and was a quarter of rasterising.
inline int32_t floor_cell(double x) {
    const int32_t truncated = static_cast<int32_t>(x);
    return truncated - (x < truncated);
}

// Marks every cell that a triangle touches (conservative). With the corners sorted by height,
// the triangle's cross-section at height y runs between the long edge (lowest to highest
// corner) and one of the two short edges; both ends move linearly in y except at the middle
// corner, so over a row band the x-range is the hull of the sections at the band's two ends
// (clipped to the triangle) and the middle corner when it lies inside the band.
void rasterise(const std::vector<Eigen::Vector2d>& points, const std::vector<Triangle>& triangles,
               BitImage& image) {
    for (const Triangle& t : triangles) {
        Eigen::Vector2d p[3] = {points[t[0]], points[t[1]], points[t[2]]};
        if (p[1].y() < p[0].y()) std::swap(p[0], p[1]);
        if (p[2].y() < p[1].y()) std::swap(p[1], p[2]);
        if (p[1].y() < p[0].y()) std::swap(p[0], p[1]);
        const double y0 = p[0].y(), y1 = p[1].y(), y2 = p[2].y();
        const int32_t row_lo = std::max(0, floor_cell(y0));
        const int32_t row_hi = std::min(image.height - 1, floor_cell(y2));
        const double long_slope = y2 > y0 ? (p[2].x() - p[0].x()) / (y2 - y0) : 0.0;
        const double low_slope = y1 > y0 ? (p[1].x() - p[0].x()) / (y1 - y0) : 0.0;
        const double high_slope = y2 > y1 ? (p[2].x() - p[1].x()) / (y2 - y1) : 0.0;
        double x_lo = 0, x_hi = 0;
        auto add = [&](double x) {
            x_lo = std::min(x_lo, x);
            x_hi = std::max(x_hi, x);
        };
        // The section at height y (y0 <= y <= y2); the corners exactly at their own heights.
        auto add_section = [&](double y) {
            if (y == y0) add(p[0].x());
            if (y == y1) add(p[1].x());
            if (y == y2) add(p[2].x());
            if (y == y0 || y == y2) return;
            add(p[0].x() + (y - y0) * long_slope);
            add(y < y1 ? p[0].x() + (y - y0) * low_slope : p[1].x() + (y - y1) * high_slope);
        };
        for (int32_t row = row_lo; row <= row_hi; ++row) {
            const double band_lo = std::max(static_cast<double>(row), y0);
            const double band_hi = std::min(row + 1.0, y2);
            x_lo = 1e300;
            x_hi = -1e300;
            add_section(band_lo);
            add_section(band_hi);
            if (y1 > band_lo && y1 < band_hi) add(p[1].x());
            const int32_t c_lo = std::max(0, floor_cell(x_lo));
            const int32_t c_hi = std::min(image.width - 1, floor_cell(x_hi));
            image.set_span(row, c_lo, c_hi);
        }
    }
}

// Transposes a 64 x 64 bit block in place (word i is row i, bit j column j): swaps of
// 32 x 32, then 16 x 16, ... sub-blocks across the diagonal (Hacker's Delight, 7-3).
void transpose_block(uint64_t block[64]) {
    uint64_t mask = 0x00000000ffffffffull;
    for (int half = 32; half > 0; half >>= 1, mask ^= mask << half) {
        for (int k = 0; k < 64; k = ((k | half) + 1) & ~half) {
            const uint64_t swap = ((block[k] >> half) ^ block[k | half]) & mask;
            block[k] ^= swap << half;
            block[k | half] ^= swap;
        }
    }
}

// A quarter turn: cell (x, y) goes to (height - 1 - y, x). The rows turned upside down, then
// transposed 64 x 64 cells at a time: linear in words, not in cells.
BitImage rotate_quarter(const BitImage& in) {
    BitImage out;
    out.resize(in.height, in.width);
    uint64_t block[64];
    for (int32_t by = 0; by < out.words; ++by) {     // 64 rows of `in`: a word of `out`
        for (int32_t bx = 0; bx < in.words; ++bx) {  // a word of `in`: 64 rows of `out`
            for (int i = 0; i < 64; ++i) {
                const int32_t y = in.height - 1 - (by * 64 + i);
                block[i] = y >= 0 ? in.row(y)[bx] : 0;
            }
            transpose_block(block);
            for (int i = 0; i < 64 && bx * 64 + i < out.height; ++i)
                out.row(bx * 64 + i)[by] = block[i];
        }
    }
    return out;
}

// The longest run of cells equal to `value` among cells 0 .. count - 1 of a bit row, a run at a
// time (count trailing zeros), not a cell at a time.
int32_t longest_run(const uint64_t* bits, int32_t count, bool value) {
    // The first cell at or after `from` that equals `want`, or count.
    auto next = [&](int32_t from, bool want) {
        int32_t w = from / 64;
        uint64_t word = (want ? bits[w] : ~bits[w]) & (~uint64_t(0) << (from % 64));
        while (word == 0) {
            if (++w * 64 >= count) return count;
            word = want ? bits[w] : ~bits[w];
        }
        return std::min(count, w * 64 + __builtin_ctzll(word));
    };
    int32_t longest = 0;
    for (int32_t x = next(0, value); x < count;) {
        const int32_t end = next(x, !value);
        longest = std::max(longest, end - x);
        x = end < count ? next(end, value) : count;
    }
    return longest;
}

// Per column: the lowest cell of the padded footprint and the highest cell of the chart itself;
// and both footprints as bit rows, for exact fitting into holes.
// An empty column's resting row: skyline - kNeverRests is below any real resting height.
constexpr int32_t kNeverRests = 1 << 30;
// Charts narrower than this are tried at every position of the strip (wider ones at steps of
// an eighth of their width, then refined).
constexpr int32_t kNarrowChart = 16;

struct Profile {
    int32_t width = 0, height = 0;
    std::vector<int32_t> top;  // highest chart row, or -1
    // The lowest padded row of each column, branch-free for the skyline search so that it
    // vectorises: resting rows (an empty column's is so high it never decides), and 1 for the
    // columns that count.
    std::vector<int32_t> resting_bottom, occupied;
    int64_t occupied_count = 0, occupied_bottom_sum = 0;  // and the sum of their bottoms
    // The first occupied column and one past the last: the occupied columns are exactly these
    // when occupied_count == occupied_end - occupied_begin (a connected chart).
    int32_t occupied_begin = 0, occupied_end = 0;
    // A few occupied columns (its first, its middle, its lowest): the highest the chart must
    // rest over these alone bounds its resting row from below at a glance. More columns
    // measured slower: the bound prunes little more and costs more. A chart narrower than
    // kNarrowChart columns, whose every position is tried, probes every occupied column: the
    // bound is then its resting row, found for all positions in one vectorised pass.
    std::vector<int32_t> probe_columns;
    int32_t words = 0;
    std::vector<uint64_t> chart_bits, padded_bits;
    // The longest run of padded cells in the middle row (the row collision tests start with):
    // a row of the layout with no free run as long has no room for the chart.
    int32_t middle_run = 0;
};

struct PreparedChart {
    Eigen::Vector2d rotation;  // cos, sin
    Eigen::Vector2d origin;    // lower corner of the rotated chart's box, in 3D units
    Profile profiles[4];       // the four quarter turns
};

Profile make_profile(const BitImage& chart, int32_t padding) {
    Profile profile;
    profile.width = chart.width;
    profile.height = chart.height;
    profile.words = chart.words;
    profile.chart_bits = chart.bits;
    profile.top.assign(chart.width, -1);
    // Padding by dilation: each row spread sideways by `padding` cells, then rows combined
    // with their `padding` neighbours above and below.
    std::vector<uint64_t> wide(chart.bits.size());
    for (int32_t y = 0; y < chart.height; ++y) {
        const uint64_t* src = chart.row(y);
        uint64_t* dst = wide.data() + static_cast<size_t>(y) * chart.words;
        std::copy(src, src + chart.words, dst);
        for (int32_t k = 0; k < padding; ++k) {
            uint64_t carry_up = 0;
            for (int32_t w = 0; w < chart.words; ++w) {  // shift towards higher x
                const uint64_t word = dst[w];
                dst[w] = word | (word << 1) | carry_up;
                carry_up = word >> 63;
            }
            uint64_t carry_down = 0;
            for (int32_t w = chart.words - 1; w >= 0; --w) {  // towards lower x
                const uint64_t word = dst[w];
                dst[w] = word | (word >> 1) | carry_down;
                carry_down = word << 63;
            }
        }
    }
    profile.padded_bits.assign(chart.bits.size(), 0);
    for (int32_t y = 0; y < chart.height; ++y) {
        uint64_t* dst = profile.padded_bits.data() + static_cast<size_t>(y) * chart.words;
        for (int32_t yy = std::max(0, y - padding); yy <= std::min(chart.height - 1, y + padding);
             ++yy) {
            const uint64_t* src = wide.data() + static_cast<size_t>(yy) * chart.words;
            for (int32_t w = 0; w < chart.words; ++w) dst[w] |= src[w];
        }
    }
    // The first row (from the bottom or from the top) that sets each column: per row only the
    // columns not seen yet are visited, so this is linear in rows times words plus columns.
    auto first_rows = [&](const std::vector<uint64_t>& bits, bool from_top,
                          std::vector<int32_t>& first) {
        std::vector<uint64_t> seen(chart.words, 0);
        for (int32_t k = 0; k < chart.height; ++k) {
            const int32_t y = from_top ? chart.height - 1 - k : k;
            const uint64_t* row = bits.data() + static_cast<size_t>(y) * chart.words;
            for (int32_t w = 0; w < chart.words; ++w) {
                for (uint64_t word = row[w] & ~seen[w]; word; word &= word - 1)
                    first[w * 64 + __builtin_ctzll(word)] = y;
                seen[w] |= row[w];
            }
        }
    };
    std::vector<int32_t> bottom(chart.width, chart.height);  // lowest padded row, or height
    first_rows(profile.chart_bits, true, profile.top);
    first_rows(profile.padded_bits, false, bottom);
    profile.resting_bottom.resize(chart.width);
    profile.occupied.resize(chart.width);
    int32_t lowest = -1;
    const int32_t spacing = chart.width < kNarrowChart ? 1 : chart.width / 2;
    for (int32_t x = 0; x < chart.width; ++x) {
        const bool occupied = bottom[x] < chart.height;
        profile.resting_bottom[x] = occupied ? bottom[x] : kNeverRests;
        profile.occupied[x] = occupied;
        if (!occupied) continue;
        if (profile.occupied_count == 0) profile.occupied_begin = x;
        profile.occupied_end = x + 1;
        ++profile.occupied_count;
        profile.occupied_bottom_sum += bottom[x];
        if (lowest < 0 || bottom[x] < bottom[lowest]) lowest = x;
        if (x % spacing == 0) profile.probe_columns.push_back(x);
    }
    if (lowest >= 0 && chart.width >= kNarrowChart) profile.probe_columns.push_back(lowest);
    profile.middle_run = longest_run(
        profile.padded_bits.data() + static_cast<size_t>(chart.height / 2) * chart.words,
        chart.width, true);
    return profile;
}

// The placed charts' cells as bit rows of a strip, growing upwards as needed.
class Occupancy {
  public:
    explicit Occupancy(int32_t strip) : strip_(strip), words_((strip + 63) / 64 + 1) {}

    // Whether `bits` (rows of `p.words` words) placed with its lower left cell at (x, y) meets
    // an occupied cell.
    bool collides(const Profile& p, const std::vector<uint64_t>& bits, int32_t x, int32_t y) const {
        const int32_t shift = x % 64, offset = x / 64;
        auto row_collides = [&](int32_t r) {
            const int32_t row = y + r;
            if (row >= rows()) return false;  // above everything placed
            const uint64_t* target = row_ptr(row) + offset;
            const uint64_t* source = bits.data() + static_cast<size_t>(r) * p.words;
            uint64_t carry = 0;
            for (int32_t w = 0; w < p.words; ++w) {
                const uint64_t word = source[w];
                const uint64_t low = (word << shift) | carry;
                carry = shift ? word >> (64 - shift) : 0;
                if (low & target[w]) return true;
            }
            return carry && (carry & target[p.words]);
        };
        // The middle row first: a chart's widest rows are near its middle, and a position in
        // a full region is rejected there at once (rounded charts barely touch their first
        // and last rows).
        const int32_t middle = p.height / 2;
        if (row_collides(middle)) return true;
        for (int32_t r = 0; r < p.height && y + r < rows(); ++r) {
            if (r != middle && row_collides(r)) return true;
        }
        return false;
    }

    void place(const Profile& p, int32_t x, int32_t y) {
        const int32_t needed = y + p.height;
        if (needed > rows()) {
            cells_.resize(static_cast<size_t>(needed) * words_, 0);
            longest_free_.resize(needed, -1);
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
        }
    }

    int32_t rows() const { return static_cast<int32_t>(cells_.size() / words_); }

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

    int32_t strip_, words_;
    std::vector<uint64_t> cells_;
    std::vector<int32_t> longest_free_;  // per row, -1 until measured
};

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

struct SkylineKernels {
    int32_t (*resting_row)(const int32_t* sky, const int32_t* rest, int32_t width, int32_t limit);
    int64_t (*skyline_under)(const int32_t* sky, const int32_t* occupied, int32_t width);
    void (*probe_bounds)(const int32_t* sky, const int32_t* rest, const int32_t* probes,
                         int32_t probe_count, int32_t count, int32_t* out);
};

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

// Places the charts (in `order`) into a strip `strip` texels wide: each lands, in its best
// quarter turn, as low as the skyline lets it, then as far left. x is searched with a step of
// an eighth of the chart's width and refined around the best step, which keeps the search
// linear in the strip width. Returns false if a chart is wider than the strip in every turn,
// or as soon as the layout grows past `max_side` texels on either side.
bool pack_strip(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                int32_t strip, bool count_waste, bool fill_holes, int32_t max_side,
                std::vector<Eigen::Vector2i>& at, std::vector<int>& quarter, int32_t& width,
                int32_t& height) {
    std::vector<int32_t> skyline(static_cast<size_t>(strip), 0);
    Occupancy occupancy(strip);
    const SkylineKernels kernels = skyline_kernels();
    width = height = 0;
    auto rest_height = [&](const Profile& p, int32_t x, int32_t limit) {
        return kernels.resting_row(skyline.data() + x, p.resting_bottom.data(), p.width, limit);
    };
    auto rest_height_at_least = [&](const Profile& p, int32_t x) {
        int32_t y;
        probe_bounds_loop(skyline.data() + x, p.resting_bottom.data(), p.probe_columns.data(),
                          static_cast<int32_t>(p.probe_columns.size()), 1, &y);
        return y;
    };
    std::vector<int32_t> bounds(static_cast<size_t>(strip));  // of every position, narrow charts
    // With count_waste, the skyline's prefix sums: under a chart whose occupied columns are
    // one run (a connected chart's are), the skyline's sum is one difference.
    std::vector<int64_t> skyline_sum(count_waste ? static_cast<size_t>(strip) + 1 : 0, 0);
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
    for (size_t c : order) {
        int64_t best_score = std::numeric_limits<int64_t>::max();
        int32_t best_x = -1, best_y = 0;
        int best_q = 0;
        for (int q = 0; q < 4; ++q) {
            const Profile& p = prepared[c].profiles[q];
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
                kernels.probe_bounds(
                    skyline.data(), p.resting_bottom.data(), p.probe_columns.data(),
                    static_cast<int32_t>(p.probe_columns.size()), last + 1, bounds.data());
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
        // Holes: a chart small against the layout may fit lower, under an overhang the
        // skyline cannot see. Scan the free cells below its skyline position in steps of a
        // quarter of its size, then let it settle down and left cell by cell.
        for (int q = 0; q < 4 && fill_holes; ++q) {
            const Profile& p = prepared[c].profiles[q];
            if (p.width > strip) continue;
            if (static_cast<int64_t>(p.width) * p.height * 8 > static_cast<int64_t>(width) * height)
                continue;
            // At most about 40 x 40 candidate positions per turn, however small the chart.
            const int32_t sx = std::max({1, p.width / 4, strip / 40});
            const int32_t sy = std::max({1, p.height / 4, height / 40});
            const int32_t best_top = best_y + prepared[c].profiles[best_q].height;
            bool found = false;
            for (int32_t y = 0; !found && y + p.height < best_top; y += sy) {
                // Every position of a row too full for the chart's middle row collides there.
                if (occupancy.longest_free(y + p.height / 2) < p.middle_run) continue;
                for (int32_t x = 0; x + p.width <= strip; x += sx) {
                    if (occupancy.collides(p, p.padded_bits, x, y)) continue;
                    int32_t fx = x, fy = y;
                    for (bool moved = true; moved;) {
                        moved = false;
                        if (fy > 0 && !occupancy.collides(p, p.padded_bits, fx, fy - 1)) {
                            --fy;
                            moved = true;
                        } else if (fx > 0 && !occupancy.collides(p, p.padded_bits, fx - 1, fy)) {
                            --fx;
                            moved = true;
                        }
                    }
                    best_x = fx;
                    best_y = fy;
                    best_q = q;
                    found = true;
                    break;
                }
            }
        }
        const Profile& p = prepared[c].profiles[best_q];
        occupancy.place(p, best_x, best_y);
        for (int32_t i = 0; i < p.width; ++i) {
            if (p.top[i] >= 0)
                skyline[best_x + i] = std::max(skyline[best_x + i], best_y + p.top[i] + 1);
        }
        for (int32_t i = best_x; i < strip && count_waste; ++i)
            skyline_sum[i + 1] = skyline_sum[i] + skyline[i];
        at[c] = Eigen::Vector2i(best_x, best_y);
        quarter[c] = best_q;
        width = std::max(width, best_x + p.width);
        height = std::max(height, best_y + p.height);
        if (std::max(width, height) > max_side) return false;
    }
    return true;
}

// Atlases of up to this many charts get the thorough search of layouts (pack_charts).
constexpr size_t kFewCharts = 100;

// Up to this many charts, the best layout's chart order is then improved by swaps: each round
// packs the order with every pair of charts swapped (same strip width and rule) and keeps the
// smallest layout, until a round finds none smaller or after kSwapRounds. A few large charts
// fill the square worst, and their order matters most. Measured against 7db2b6e, 2 threads:
// halftunnel (7 charts) coverage 0.623 -> 0.662, pack 7.4 -> 12.4 ms; face (12) 0.711 ->
// 0.745, 13.2 -> 20.9 ms; 3holes (11) and fandisk (4) unchanged, beetle (9) 0.628 -> 0.629.
// Four rounds found nothing more on these five; 8 rounds of 8 random swaps instead ranged
// 0.653 to 0.683 on halftunnel with the seed (7 seeds tried).
constexpr size_t kSwappedCharts = 16;
constexpr int kSwapRounds = 2;

}  // namespace

ChartBox smallest_bounding_box(const std::vector<Eigen::Vector2d>& uv,
                               const std::vector<Triangle>& triangles,
                               const std::vector<int32_t>& boundary) {
    std::vector<Eigen::Vector2d> outline(boundary.size());
    for (size_t i = 0; i < boundary.size(); ++i) outline[i] = uv[boundary[i]];
    ChartBox box;
    box.rotation = best_rotation(outline);
    const Eigen::Vector2d r = box.rotation;
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (const Eigen::Vector2d& p : uv) {
        const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(), -r.y() * p.x() + r.x() * p.y());
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    double area = 0;
    for (const Triangle& t : triangles) {
        const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
        area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    const double box_area = (hi.x() - lo.x()) * (hi.y() - lo.y());
    box.fill = box_area > 0 ? std::min(1.0, area / box_area) : 1.0;
    return box;
}

PackResult pack_charts(const std::vector<PackInput>& charts, const PackSettings& settings,
                       ThreadPool& pool) {
    PackResult result;
    const size_t count = charts.size();
    result.uv.resize(count);
    if (count == 0) return result;
    const int32_t padding = std::max(0, settings.padding);
    const double resolution = std::max(1, settings.resolution);

    // Turn every chart to its smallest box.
    std::vector<PreparedChart> prepared(count);
    std::vector<Eigen::Vector2d> extent(count);
    double total_area = 0;
    for (size_t c = 0; c < count; ++c) {
        const std::vector<Eigen::Vector2d>& uv = *charts[c].uv;
        prepared[c].rotation = charts[c].rotation;
        const Eigen::Vector2d r = prepared[c].rotation;
        Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
        for (const Eigen::Vector2d& p : uv) {
            const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(), -r.y() * p.x() + r.x() * p.y());
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
        prepared[c].origin = lo;
        extent[c] = hi - lo;
        for (const Triangle& t : *charts[c].triangles) {
            const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            total_area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
    }
    // Three orders to place the charts in, largest first by the longer side of their box, by
    // its area and by its shorter side (ties by index): which packs best varies from mesh to
    // mesh (measured: lion, suzanne and teapot each best in a different one).
    auto largest_first = [&](auto size_of) {
        std::vector<size_t> order(count);
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return size_of(a) > size_of(b); });
        return order;
    };
    std::vector<std::vector<size_t>> orders = {
        largest_first([&](size_t c) { return std::max(extent[c].x(), extent[c].y()); }),
        largest_first([&](size_t c) { return extent[c].x() * extent[c].y(); }),
        largest_first([&](size_t c) { return std::min(extent[c].x(), extent[c].y()); })};
    // Charts of one size (thousands of equal quads) come in the same order every way.
    for (size_t k = orders.size(); k-- > 1;) {
        if (std::find(orders.begin(), orders.begin() + k, orders[k]) != orders.begin() + k)
            orders.erase(orders.begin() + k);
    }
    const std::vector<size_t>& order = orders[0];

    // Pack at a trial density, then raise it by the room left and pack again, so the final
    // layout is packed at (nearly) its final texel size and the padding is not inflated.
    double scale = std::sqrt(0.45 * resolution * resolution / std::max(total_area, 1e-300));
    // No chart may be longer than the atlas.
    double longest = 0;
    for (const Eigen::Vector2d& e : extent) longest = std::max({longest, e.x(), e.y()});
    scale = std::min(scale, (resolution - 2.0 * padding - 2.0) / std::max(longest, 1e-300));
    const int32_t limit = static_cast<int32_t>(resolution);
    // Charts, strip widths and layouts are independent: each runs on its own thread and writes
    // only its own slot, so the result does not depend on the thread count.
    auto rasterise_all = [&](double at_scale, int32_t& widest) {
        std::vector<int32_t> narrow_side(count);
        parallel_for_each(pool, count, [&](size_t c) {
            BitImage raster;
            raster.resize(
                static_cast<int32_t>(std::ceil(extent[c].x() * at_scale)) + 1 + 2 * padding,
                static_cast<int32_t>(std::ceil(extent[c].y() * at_scale)) + 1 + 2 * padding);
            const Eigen::Vector2d r = prepared[c].rotation;
            std::vector<Eigen::Vector2d> points(charts[c].uv->size());
            for (size_t v = 0; v < points.size(); ++v) {
                const Eigen::Vector2d& p = (*charts[c].uv)[v];
                const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(),
                                        -r.y() * p.x() + r.x() * p.y());
                points[v] = (q - prepared[c].origin) * at_scale + Eigen::Vector2d(padding, padding);
            }
            rasterise(points, *charts[c].triangles, raster);
            for (int q = 0; q < 4; ++q) {
                prepared[c].profiles[q] = make_profile(raster, padding);
                if (q < 3) raster = rotate_quarter(raster);
            }
            narrow_side[c] = std::min(raster.width, raster.height);
        });
        widest = std::max(1, *std::max_element(narrow_side.begin(), narrow_side.end()));
    };
    struct Packed {
        std::vector<Eigen::Vector2i> at;
        std::vector<int> quarter;
        int32_t width = 0, height = 0;
        double area() const { return static_cast<double>(width) * height; }
    };
    // Every order, strip width and scoring rule, each packed with holes filled, or on the
    // skyline alone where filling holes overflows the atlas; the smallest rectangle wins (ties:
    // the earlier trial). `density_strip` is among the widths: its skyline packing is the one
    // the density was fitted to, so some trial always fits.
    // The side of the square as large as the charts' padded boxes together, in cells.
    auto square_side = [&] {
        double area_cells = 0;
        for (size_t c = 0; c < count; ++c) {
            area_cells +=
                static_cast<double>(prepared[c].profiles[0].width) * prepared[c].profiles[0].height;
        }
        return static_cast<int32_t>(std::sqrt(area_cells));
    };
    auto best_layout = [&](int32_t widest, int32_t density_strip) {
        std::vector<int32_t> widths = {density_strip};
        const int32_t square = square_side();
        // Strip widths geometrically spaced from 0.83 to 1.8 times the square's side (k = 2 ..
        // 11 of a series from 0.7). The density is fitted to the square strip, so narrower
        // strips grow too tall: 0.7 and 0.76 fitted none of the 16 shared meshes.
        for (int k = 2; k < 12 && count > 1; ++k) {
            const double f = 0.7 * portable::pow(1.8 / 0.7, k / 11.0);
            widths.push_back(std::clamp(static_cast<int32_t>(square * f), widest, limit));
        }
        std::sort(widths.begin(), widths.end());
        widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
        // Up to kFewCharts charts, where each chart's place matters and a packing is cheap,
        // every order is tried and every trial fills holes (on the skyline alone where that
        // overflows the atlas). With more, one order on the skyline alone, and holes filled in
        // the two best layouts: for 2,000 separate triangles the rest took three times as long
        // and found no better layout.
        const bool few = count <= kFewCharts;
        const size_t per_order = 2 * widths.size();
        const size_t trials = (few ? orders.size() : 1) * per_order;
        std::vector<Packed> packed(trials);
        std::vector<char> fits(trials, 0);
        auto pack_order = [&](const std::vector<size_t>& chart_order, int32_t width,
                              bool count_waste, bool holes, Packed& p) {
            p.at.resize(count);
            p.quarter.resize(count);
            return pack_strip(prepared, chart_order, width, count_waste, holes, limit, p.at,
                              p.quarter, p.width, p.height);
        };
        auto pack_trial = [&](size_t trial, bool holes, Packed& p) {
            return pack_order(orders[trial / per_order], widths[trial % per_order / 2],
                              trial % 2 == 1, holes, p);
        };
        parallel_for_each(pool, trials, [&](size_t trial) {
            fits[trial] = (few && pack_trial(trial, true, packed[trial])) ||
                          pack_trial(trial, false, packed[trial]);
        });
        if (!few) {
            std::vector<size_t> ranked;
            for (size_t trial = 0; trial < trials; ++trial) {
                if (fits[trial]) ranked.push_back(trial);
            }
            std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) {
                return packed[a].area() < packed[b].area();
            });
            ranked.resize(std::min<size_t>(ranked.size(), 2));
            std::vector<Packed> with_holes(ranked.size());
            std::vector<char> holes_fit(ranked.size(), 0);
            parallel_for_each(pool, ranked.size(), [&](size_t k) {
                holes_fit[k] = pack_trial(ranked[k], true, with_holes[k]);
            });
            for (size_t k = 0; k < ranked.size(); ++k) {
                if (holes_fit[k]) packed[ranked[k]] = std::move(with_holes[k]);
            }
        }
        size_t best = trials;
        for (size_t trial = 0; trial < trials; ++trial) {
            if (fits[trial] && (best == trials || packed[trial].area() < packed[best].area()))
                best = trial;
        }
        if (best == trials) throw Error(ErrorCode::kInternal, "no chart layout fits the atlas");
        Packed layout = std::move(packed[best]);
        if (count < 2 || count > kSwappedCharts) return layout;
        std::vector<size_t> kept_order = orders[best / per_order];
        const int32_t width = widths[best % per_order / 2];
        const bool count_waste = best % 2 == 1;
        for (int round = 0; round < kSwapRounds; ++round) {
            std::vector<std::vector<size_t>> variants;
            for (size_t i = 0; i < count; ++i) {
                for (size_t j = i + 1; j < count; ++j) {
                    variants.push_back(kept_order);
                    std::swap(variants.back()[i], variants.back()[j]);
                }
            }
            std::vector<Packed> tried(variants.size());
            std::vector<char> tried_fits(variants.size(), 0);
            parallel_for_each(pool, variants.size(), [&](size_t k) {
                tried_fits[k] = pack_order(variants[k], width, count_waste, true, tried[k]);
            });
            bool improved = false;
            for (size_t k = 0; k < variants.size(); ++k) {
                if (tried_fits[k] && tried[k].area() < layout.area()) {
                    layout = std::move(tried[k]);
                    kept_order = variants[k];
                    improved = true;
                }
            }
            if (!improved) break;
        }
        return layout;
    };

    // The strip the density is fitted in: as wide as the square of the charts' box areas (a
    // single chart: its longer side).
    auto density_strip = [&](int32_t widest) {
        if (count == 1)
            return std::max(prepared[0].profiles[0].width, prepared[0].profiles[0].height);
        return std::clamp(square_side(), widest, limit);
    };
    // The density: the largest for which a skyline packing into a strip of the square's width
    // fits, found in a few steps (each scales by the room the last layout left). Only then are
    // all orders, strip widths and rules tried, at that density.
    double fitted_scale = -1;
    int32_t widest = 1;
    for (int attempt = 0; attempt < 24; ++attempt) {
        rasterise_all(scale, widest);
        const int32_t strip = density_strip(widest);
        std::vector<Eigen::Vector2i> at(count);
        std::vector<int> quarter(count);
        int32_t width = 0, height = 0;
        const bool fits =
            pack_strip(prepared, order, strip, false, false, limit, at, quarter, width, height);
        if (!fits) {
            if (fitted_scale > 0) break;
            scale *= 0.85;  // nothing fitted yet: lower the density
            continue;
        }
        fitted_scale = scale;
        const double room = resolution / std::max(std::max(width, height), 1);
        if (room < 1.02 || attempt >= 3) break;
        scale *= std::min(room, 1.5) * 0.995;
    }
    if (fitted_scale != scale) rasterise_all(fitted_scale, widest);
    scale = fitted_scale;
    const Packed best = best_layout(widest, density_strip(widest));
    const std::vector<Eigen::Vector2i>& placed = best.at;
    const std::vector<int>& turn = best.quarter;

    // Positions in the layout, in cells (continuous).
    Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
    for (size_t c = 0; c < count; ++c) {
        const Eigen::Vector2d r = prepared[c].rotation;
        const Profile& p = prepared[c].profiles[turn[c]];
        const int32_t w0 = turn[c] % 2 ? p.height : p.width;  // the unrotated raster's size
        const int32_t h0 = turn[c] % 2 ? p.width : p.height;
        result.uv[c].resize(charts[c].uv->size());
        for (size_t v = 0; v < result.uv[c].size(); ++v) {
            const Eigen::Vector2d& src = (*charts[c].uv)[v];
            const Eigen::Vector2d q(r.x() * src.x() + r.y() * src.y(),
                                    -r.y() * src.x() + r.x() * src.y());
            // Position in the unrotated padded raster frame (texel units, continuous); the
            // quarter turns map the cell (x, y) to (h - 1 - y, x), i.e. the point (x, y) to
            // (h - y, x) for continuous coordinates.
            double x = (q.x() - prepared[c].origin.x()) * scale + padding;
            double y = (q.y() - prepared[c].origin.y()) * scale + padding;
            int32_t cur_w = w0, cur_h = h0;
            for (int k = 0; k < turn[c]; ++k) {
                const double nx = cur_h - y, ny = x;
                x = nx;
                y = ny;
                std::swap(cur_w, cur_h);
            }
            const Eigen::Vector2d at(placed[c].x() + x, placed[c].y() + y);
            result.uv[c][v] = at;
            low = low.cwiseMin(at);
            high = high.cwiseMax(at);
        }
    }
    // The padding matters between charts, not at the atlas's border: the layout is cropped to
    // the charts themselves. It is stretched uniformly until its longer side is the resolution
    // (a factor >= 1, which only widens the gaps between charts), then normalised per axis to
    // the atlas's texels: texel space stays isotropic, and the charts span [0, 1] on one axis
    // and all but a fraction of a texel on the other.
    const double span_x = std::max(high.x() - low.x(), 0.0);
    const double span_y = std::max(high.y() - low.y(), 0.0);
    const double span = std::max(span_x, span_y);
    auto texels = [](double length) {
        return std::max(1, static_cast<int32_t>(std::ceil(length - 1e-9)));
    };
    double grow = span > 0 ? resolution / span : 1.0;
    // The shorter side loses up to a texel to rounding up (0.5% of alligator's 180): shrinking
    // the layout until that side is a whole number of texels loses less of the longer one.
    const double shorter = std::min(span_x, span_y);
    if (shorter > 0) {
        const double exact = std::floor(shorter * grow) / shorter;
        auto fill = [&](double g) {
            return span_x * g / texels(span_x * g) * (span_y * g / texels(span_y * g));
        };
        if (exact >= 1.0 && fill(exact) > fill(grow)) grow = exact;
    }
    result.width = texels(span_x * grow);
    result.height = texels(span_y * grow);
    const double to_u = grow / result.width, to_v = grow / result.height;
    for (std::vector<Eigen::Vector2d>& chart_uv : result.uv) {
        for (Eigen::Vector2d& at : chart_uv) {
            at = Eigen::Vector2d(std::min(1.0, (at.x() - low.x()) * to_u),
                                 std::min(1.0, (at.y() - low.y()) * to_v));
        }
    }
    return result;
}

}  // namespace raps
