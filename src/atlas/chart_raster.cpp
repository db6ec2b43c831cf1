#include "atlas/chart_raster.h"

#include <algorithm>
#include <numeric>
#include <utility>

#include "core/fill_in_runs.h"

namespace raps {
namespace {

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

// Where the longest run of padded cells in row `row` of a profile begins (the first, of
// equal runs).
int32_t longest_run_begin(const Profile& p, int32_t row) {
    const uint64_t* bits = p.padded_bits.data() + static_cast<size_t>(row) * p.words;
    int32_t best = 0, best_length = -1;
    for (int32_t x = 0; x < p.width;) {
        if (!(bits[x / 64] >> (x % 64) & 1)) {
            ++x;
            continue;
        }
        int32_t end = x;
        while (end < p.width && (bits[end / 64] >> (end % 64) & 1)) ++end;
        if (end - x > best_length) {
            best = x;
            best_length = end - x;
        }
        x = end;
    }
    return best;
}

// The cells one triangle touches (rasterise, for one; a segment as a triangle with a repeated
// corner).
void rasterise_triangle(Eigen::Vector2d p0, Eigen::Vector2d p1, Eigen::Vector2d p2,
                        BitImage& image) {
    Eigen::Vector2d p[3] = {p0, p1, p2};
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

// ceil(x) for the raster's coordinates, as floor_cell.
int32_t ceil_cell(double x) {
    return -floor_cell(-x);
}

}  // namespace

void rasterise(const std::vector<Eigen::Vector2d>& points, const std::vector<Triangle>& triangles,
               BitImage& image) {
    for (const Triangle& t : triangles)
        rasterise_triangle(points[t[0]], points[t[1]], points[t[2]], image);
}

ChartOutline chart_outline(const std::vector<Eigen::Vector2d>& uv,
                           const std::vector<Triangle>& triangles, const ProgressSpan& progress) {
    ChartOutline outline;
    const int64_t count = static_cast<int64_t>(triangles.size());
    // Directed edges bucketed by their lower vertex (a counting sort), each bucket then sorted
    // by its higher vertex: linear, where one sort of all edges was a second without a progress
    // call at 3.3M triangles. Each bucket holds (higher vertex, +1 when directed low to high).
    bool positive = false, negative = false;
    std::vector<int32_t> offset(uv.size() + 1, 0);
    progress.part(0.0, 0.3).in_runs(count, [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            const Triangle& t = triangles[i];
            const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            const double area = a.x() * b.y() - a.y() * b.x();
            positive = positive || area > 0;
            negative = negative || area < 0;
            for (int k = 0; k < 3; ++k) ++offset[std::min(t[k], t[(k + 1) % 3]) + 1];
        }
    });
    // Triangles turned both ways fold the chart over itself: where they overlap, the outline's
    // winding cancels, though the triangles cover the cells.
    if (positive && negative) return outline;
    std::partial_sum(offset.begin(), offset.end(), offset.begin());
    std::vector<std::pair<int32_t, int32_t>> by_low;
    assign_in_runs(by_low, static_cast<size_t>(3 * count), {0, 0}, progress.part(0.3, 0.4));
    std::vector<int32_t> cursor(offset.begin(), offset.end() - 1);
    progress.part(0.4, 0.7).in_runs(count, [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            const Triangle& t = triangles[i];
            for (int k = 0; k < 3; ++k) {
                const int32_t from = t[k], to = t[(k + 1) % 3];
                by_low[cursor[std::min(from, to)]++] = {std::max(from, to), from < to ? 1 : -1};
            }
        }
    });
    bool usable = true;
    const int64_t vertex_count = static_cast<int64_t>(uv.size());
    progress.part(0.7, 1.0).in_runs(vertex_count, [&](int64_t begin, int64_t end) {
        for (int64_t low = begin; low < end && usable; ++low) {
            const auto first = by_low.begin() + offset[low],
                       last = by_low.begin() + offset[low + 1];
            std::sort(first, last);
            for (auto k = first; k != last;) {
                auto group_end = k + 1;
                while (group_end != last && group_end->first == k->first) ++group_end;
                // An edge of three triangles or more, or of two turned the same way.
                if (group_end - k > 2 || (group_end - k == 2 && k->second == (k + 1)->second)) {
                    usable = false;
                    break;
                }
                if (group_end - k == 1) {
                    const int32_t a = static_cast<int32_t>(low), b = k->first;
                    outline.edges.push_back(k->second > 0 ? std::array<int32_t, 2>{a, b}
                                                          : std::array<int32_t, 2>{b, a});
                }
                k = group_end;
            }
        }
    });
    if (!usable) outline.edges.clear();
    outline.usable = usable;
    return outline;
}

void rasterise_chart(const std::vector<Eigen::Vector2d>& points,
                     const std::vector<Triangle>& triangles, const ChartOutline& outline,
                     BitImage& image) {
    if (!outline.usable) {
        rasterise(points, triangles, image);
        return;
    }
    // The cells the outline touches: every cell a triangle touches but does not hold whole.
    for (const auto& e : outline.edges)
        rasterise_triangle(points[e[0]], points[e[1]], points[e[1]], image);
    // The cells held whole: their centres, which the outline winds around. Per row, where the
    // edges cross its centre line (each edge counts where y_a <= y < y_b, so a corner on the line
    // counts once), sorted, then the spans of nonzero winding.
    const int32_t rows = image.height;
    std::vector<int32_t> first(static_cast<size_t>(rows) + 1, 0);
    auto row_range = [&](const std::array<int32_t, 2>& e, int32_t& lo, int32_t& hi) {
        const double ya = points[e[0]].y(), yb = points[e[1]].y();
        // Rows r with r + 0.5 in [min, max).
        lo = std::max(0, ceil_cell(std::min(ya, yb) - 0.5));
        hi = std::min(rows, ceil_cell(std::max(ya, yb) - 0.5));
    };
    for (const auto& e : outline.edges) {
        int32_t lo, hi;
        row_range(e, lo, hi);
        for (int32_t r = lo; r < hi; ++r) ++first[r + 1];
    }
    for (int32_t r = 0; r < rows; ++r) first[r + 1] += first[r];
    std::vector<std::pair<double, int>> crossings(static_cast<size_t>(first[rows]));
    std::vector<int32_t> fill = first;
    for (const auto& e : outline.edges) {
        int32_t lo, hi;
        row_range(e, lo, hi);
        const Eigen::Vector2d& a = points[e[0]];
        const Eigen::Vector2d& b = points[e[1]];
        const double slope = (b.x() - a.x()) / (b.y() - a.y());
        for (int32_t r = lo; r < hi; ++r)
            crossings[fill[r]++] = {a.x() + (r + 0.5 - a.y()) * slope, b.y() > a.y() ? 1 : -1};
    }
    for (int32_t r = 0; r < rows; ++r) {
        const auto begin = crossings.begin() + first[r], end = crossings.begin() + first[r + 1];
        std::sort(begin, end);
        int winding = 0;
        for (auto c = begin; c != end; ++c) {
            winding += c->second;
            if (winding == 0 || c + 1 == end) continue;
            // Cells whose centre x + 0.5 lies in [c.x, next.x).
            const int32_t lo = std::max(0, ceil_cell(c->first - 0.5));
            const int32_t hi = std::min(image.width, ceil_cell((c + 1)->first - 0.5));
            image.set_span(r, lo, hi - 1);
        }
    }
}

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

int32_t next_cell(const uint64_t* bits, int32_t count, int32_t from, bool value) {
    if (from >= count) return count;
    int32_t w = from / 64;
    uint64_t word = (value ? bits[w] : ~bits[w]) & (~uint64_t(0) << (from % 64));
    while (word == 0) {
        if (++w * 64 >= count) return count;
        word = value ? bits[w] : ~bits[w];
    }
    return std::min(count, w * 64 + __builtin_ctzll(word));
}

int32_t longest_run(const uint64_t* bits, int32_t count, bool value) {
    auto next = [&](int32_t from, bool want) { return next_cell(bits, count, from, want); };
    int32_t longest = 0;
    for (int32_t x = next(0, value); x < count;) {
        const int32_t end = next(x, !value);
        longest = std::max(longest, end - x);
        x = end < count ? next(end, value) : count;
    }
    return longest;
}

Profile make_profile(BitImage chart, int32_t padding) {
    Profile profile;
    profile.width = chart.width;
    profile.height = chart.height;
    profile.words = chart.words;
    profile.padded_bits = chart.bits;
    profile.chart_bits = std::move(chart.bits);
    profile.top.assign(chart.width, -1);
    // Padding by dilation: each row spread sideways by `padding` cells, then each row combined
    // with its `padding` neighbours above and below, in place: `padding` passes that add the
    // row below (rows visited downwards, so each adds its neighbour as it was), then `padding`
    // that add the row above.
    const int32_t words = chart.words;
    for (int32_t y = 0; y < chart.height; ++y) {
        uint64_t* dst = profile.padded_bits.data() + static_cast<size_t>(y) * words;
        for (int32_t k = 0; k < padding; ++k) {
            uint64_t carry_up = 0;
            for (int32_t w = 0; w < words; ++w) {  // shift towards higher x
                const uint64_t word = dst[w];
                dst[w] = word | (word << 1) | carry_up;
                carry_up = word >> 63;
            }
            uint64_t carry_down = 0;
            for (int32_t w = words - 1; w >= 0; --w) {  // towards lower x
                const uint64_t word = dst[w];
                dst[w] = word | (word >> 1) | carry_down;
                carry_down = word << 63;
            }
        }
    }
    auto padded_row = [&](int32_t y) {
        return profile.padded_bits.data() + static_cast<size_t>(y) * words;
    };
    auto add_row = [&](int32_t to, int32_t from) {
        for (int32_t w = 0; w < words; ++w) padded_row(to)[w] |= padded_row(from)[w];
    };
    for (int32_t k = 0; k < padding; ++k) {
        for (int32_t y = chart.height - 1; y > 0; --y) add_row(y, y - 1);
    }
    for (int32_t k = 0; k < padding; ++k) {
        for (int32_t y = 0; y + 1 < chart.height; ++y) add_row(y, y + 1);
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
    profile.middle_begin = longest_run_begin(profile, chart.height / 2);
    for (int32_t eighths : {2, 6, 3, 5}) {
        const int32_t r = eighths * chart.height / 8;
        if (r == chart.height / 2) continue;
        profile.sample_runs.push_back(r);
        profile.sample_runs.push_back(longest_run_begin(profile, r));
        profile.sample_runs.push_back(longest_run(
            profile.padded_bits.data() + static_cast<size_t>(r) * chart.words, chart.width, true));
    }
    profile.word_span.resize(2 * static_cast<size_t>(chart.height));
    for (int32_t y = 0; y < chart.height; ++y) {
        const uint64_t* row = profile.padded_bits.data() + static_cast<size_t>(y) * chart.words;
        int32_t first = 0, end = chart.words;
        while (first < end && row[first] == 0) ++first;
        while (end > first && row[end - 1] == 0) --end;
        profile.word_span[2 * y] = first;
        profile.word_span[2 * y + 1] = end;
    }
    return profile;
}

}  // namespace raps
