// The charts' footprints for packing: a chart's uv triangles rasterised conservatively into a
// bit image of cells (texels, or blocks of them), turned by quarter turns, and summarised per
// column for the skyline search (skyline_packing.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

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

// Point p turned by a chart's rotation r = (cos, sin): the uvs both packers rasterise.
inline Eigen::Vector2d turned(const Eigen::Vector2d& r, const Eigen::Vector2d& p) {
    return Eigen::Vector2d(r.x() * p.x() + r.y() * p.y(), -r.y() * p.x() + r.x() * p.y());
}

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
               BitImage& image);

// A chart's boundary for rasterise_chart: its edges (a, b) directed as their triangles give
// them. Not usable (the triangles are rasterised instead) where the triangles turn both ways
// (a fold: where it overlaps itself the outline's winding cancels) or an edge does not join
// two triangles turned the same way at most. Measured once per chart: rasterising a chart's
// triangles at every trial density was a tenth to a fifth of small meshes' atlases.
struct ChartOutline {
    std::vector<std::array<int32_t, 2>> edges;
    bool usable = false;
};
// Linear in the triangles; `progress` is told its fraction every kItemsPerReport of them.
ChartOutline chart_outline(const std::vector<Eigen::Vector2d>& uv,
                           const std::vector<Triangle>& triangles,
                           const ProgressSpan& progress = {});

// The cells rasterise() marks, from the outline when it is usable: the cells its edges touch
// (every cell a triangle touches but does not hold whole) and the cells whose centre it winds
// around (those held whole). Linear in the outline and the rows, not in the triangles.
void rasterise_chart(const std::vector<Eigen::Vector2d>& points,
                     const std::vector<Triangle>& triangles, const ChartOutline& outline,
                     BitImage& image);

// A quarter turn: cell (x, y) goes to (height - 1 - y, x). The rows turned upside down, then
// transposed 64 x 64 cells at a time: linear in words, not in cells.
BitImage rotate_quarter(const BitImage& in);

// The first of cells from .. count - 1 of a bit row that equals `value`, or count: a word at a
// time (count trailing zeros).
int32_t next_cell(const uint64_t* bits, int32_t count, int32_t from, bool value);

// The longest run of cells equal to `value` among cells 0 .. count - 1 of a bit row, a run at a
// time (count trailing zeros), not a cell at a time.
int32_t longest_run(const uint64_t* bits, int32_t count, bool value);

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
    int32_t middle_begin = 0;  // where that run begins (the first, of equal runs)
    // A few more rows as (r, begin, length) of the longest run of padded cells in row r: a
    // position whose layout row y + r has no free run around that run cannot take the chart.
    std::vector<int32_t> sample_runs;
    // Per row of padded_bits: its first word with a cell and one past its last (collision
    // tests skip the rest; the rows of a rounded chart are short near its ends).
    std::vector<int32_t> word_span;
};

// The profile of a chart's cells, its padded footprint dilated by `padding` cells.
Profile make_profile(BitImage chart, int32_t padding);

}  // namespace raps
