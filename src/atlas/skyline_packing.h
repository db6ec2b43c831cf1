// The skyline search that places charts into a strip of cells: each chart lands, in its best
// allowed quarter turn, as low as the skyline (the top of what is placed, per column) lets it,
// then as far left, or lower still in a hole under an overhang when asked. The search's inner
// loops are integer arithmetic, the same on every processor.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "atlas/chart_raster.h"

namespace raps {

struct PreparedChart {
    Eigen::Vector2d rotation;  // cos, sin
    Eigen::Vector2d origin;    // lower corner of the rotated chart's box, in 3D units
    // The four quarter turns of each way the chart is turned before them (placement index q:
    // the way q / 4, turned q % 4 quarters; page_packing uses one way, `rotation`).
    std::vector<Profile> profiles = std::vector<Profile>(4);
    int turns = 4;  // how many of them may be used (1: the chart is never turned)
};

constexpr int kAllTurns = 1 << 20;

struct SkylineKernels {
    int32_t (*resting_row)(const int32_t* sky, const int32_t* rest, int32_t width, int32_t limit);
    int64_t (*skyline_under)(const int32_t* sky, const int32_t* occupied, int32_t width);
    void (*probe_bounds)(const int32_t* sky, const int32_t* rest, const int32_t* probes,
                         int32_t probe_count, int32_t count, int32_t* out);
};

class Occupancy;

struct Placement {
    int32_t x = 0, y = 0;  // the profile's lower left cell
    int quarter = 0;       // quarter turns counter-clockwise
};

// One strip `strip` cells wide, open upwards. find() searches the place of a chart in its allowed
// turns (lowest top first; with count_waste, the fewest cells left empty under it); commit()
// takes it. A copy is an independent layout (for placing tentatively).
class SkylineStrip {
  public:
    // turn_limit: placement indices from it on are not used (4: the chart's first way alone).
    SkylineStrip(int32_t strip, bool count_waste, bool fill_holes, int turn_limit = kAllTurns);
    SkylineStrip(const SkylineStrip& other);
    SkylineStrip& operator=(const SkylineStrip&) = delete;
    ~SkylineStrip();

    // false if the chart is wider than the strip in every allowed turn.
    bool find(const PreparedChart& chart, Placement& place);
    void commit(const PreparedChart& chart, const Placement& place);

    const int32_t strip;
    const bool count_waste, fill_holes;
    const int turn_limit;
    int32_t width = 0, height = 0;  // the layout so far, in cells

  private:
    // Moves `place` lower, into a hole under an overhang, where the chart fits there.
    void find_hole(const PreparedChart& chart, Placement& place);
    // The chart's left columns at which its middle row and each sample row (Profile) lie in
    // one free run of the layout's row they land on with the chart at row y: ascending
    // intervals [lo, hi] as pairs in `out`. Any other column collides.
    void run_positions(const Profile& p, int32_t y, std::vector<int32_t>& out);
    // Whether each of the chart's sample rows (Profile::sample_runs) has a free run as long in
    // the layout's row it lands on with the chart at row y: else no position of the row fits.
    bool room_in_samples(const Profile& p, int32_t y);
    // Lets a chart at (x, y) slide down and left while it collides with nothing.
    void settle(const Profile& p, int32_t& x, int32_t& y) const;

    std::vector<int32_t> skyline_;
    std::unique_ptr<Occupancy> occupancy_;
    SkylineKernels kernels_;
    std::vector<int32_t> bounds_;  // of every position, narrow charts
    // With count_waste, the skyline's prefix sums: under a chart whose occupied columns are
    // one run (a connected chart's are), the skyline's sum is one difference.
    std::vector<int64_t> skyline_sum_;
    int64_t hole_tests_left_;           // of the layout's hole searches (skyline_packing.cpp)
    std::vector<int32_t> run_scratch_;  // run_positions's intervals under construction
    std::vector<int32_t> intervals_;    // find_hole's, kept for the next chart
};

enum class StripResult {
    kFits,
    kTooLarge,  // a chart is wider than the strip in every turn, or a side grew past max_side
    kBeaten,    // the layout's cost grew past `beaten_above`
};

// How layouts are ranked: by the side of the square that holds them (the square texture their
// uvs are normalised to), then by their area. Both only grow as charts are added. Sides are at
// most 2^14 cells (the largest resolution), so the area fits below the side's bits.
inline int64_t layout_cost(int32_t width, int32_t height) {
    return (static_cast<int64_t>(std::max(width, height)) << 32) +
           static_cast<int64_t>(width) * height;
}

// Places the charts (in `order`) into a strip `strip` cells wide, one after another. x is
// searched with a step of an eighth of the chart's width and refined around the best step,
// which keeps the search linear in the strip width. Stops as soon as a chart is wider than the
// strip in every turn, or the layout grows past `max_side` cells on either side, or (with
// `beaten_above`) its layout_cost exceeds that bound: the cost only grows as charts are added,
// so a layout of a search that already has a cheaper one is given up early. The bound
// may fall while the layout is packed (other trials finishing); which layouts are given up then
// depends on the schedule, never which layout is smallest.
StripResult pack_strip(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                       int32_t strip, bool count_waste, bool fill_holes, int32_t max_side,
                       std::vector<Eigen::Vector2i>& at, std::vector<int>& quarter, int32_t& width,
                       int32_t& height, int turn_limit = kAllTurns,
                       const std::atomic<int64_t>* beaten_above = nullptr);

// Orders to place charts in, largest first by the longer side of their box (`extents`), by its
// area and by its shorter side (ties by index), each once: charts of one size (thousands of
// equal quads) come in the same order every way. Which packs best varies from mesh to mesh and
// with the density (measured: lion, suzanne and teapot each best in a different one). With
// `further`, three more: by the box's width, its height (as the chart is turned before its
// quarter turns) and its perimeter.
std::vector<std::vector<size_t>> size_orders(const std::vector<Eigen::Vector2d>& extents,
                                             bool further = false);

}  // namespace raps
