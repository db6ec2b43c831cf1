// A chart's raster from its outline (rasterise_chart, src/atlas/chart_raster.h) against the
// raster of its triangles (rasterise): the same cells, bit for bit, on charts of every kind the
// packers meet, turned, scaled and moved on fixed pseudo-random draws; and charts whose outline
// cannot stand for them (folded, an edge of three triangles) rasterised by their triangles. A
// test of an internal part, as test_portable_math is: the C ABI shows the packed layout, never
// a raster, and a cell the outline missed would only show as an overlap where a later chart
// happened to fall into it.
#include <cmath>
#include <cstdint>
#include <vector>

// Before cmocka.h, whose fail() and skip() macros would rename the standard library's.
#include "atlas/chart_raster.h"
#include "support/split_mix.h"

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

namespace {

struct Chart {
    std::vector<Eigen::Vector2d> uv;
    std::vector<raps::Triangle> triangles;
};

// An n x m grid of unit squares, two counter-clockwise triangles each; its interior vertices
// moved by up to `jitter` (a fraction of a square, below half: no triangle turns over), and the
// squares `left_out` names left out (a hole, a notch).
template <typename LeftOut>
Chart grid(int n, int m, double jitter, Random& random, LeftOut left_out) {
    Chart chart;
    for (int j = 0; j <= m; ++j) {
        for (int i = 0; i <= n; ++i) {
            const bool inside = i > 0 && i < n && j > 0 && j < m;
            const double dx = inside ? random.uniform(-jitter, jitter) : 0.0;
            const double dy = inside ? random.uniform(-jitter, jitter) : 0.0;
            chart.uv.emplace_back(i + dx, j + dy);
        }
    }
    auto at = [&](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < m; ++j) {
        for (int i = 0; i < n; ++i) {
            if (left_out(i, j)) continue;
            chart.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            chart.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    return chart;
}

Chart grid(int n, int m, double jitter, Random& random) {
    return grid(n, m, jitter, random, [](int, int) { return false; });
}

// The chart turned by `angle`, scaled by `scale` and moved by `offset`: points in cells.
std::vector<Eigen::Vector2d> placed(const Chart& chart, double angle, double scale,
                                    const Eigen::Vector2d& offset) {
    std::vector<Eigen::Vector2d> points;
    const double c = std::cos(angle), s = std::sin(angle);
    for (const Eigen::Vector2d& p : chart.uv)
        points.push_back(Eigen::Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) * scale +
                         offset);
    return points;
}

// Both rasters of `chart` at many placements in an image of 200 x 200 cells; the same bits.
void expect_same_cells(const Chart& chart, Random& random, bool outline_usable) {
    const raps::ChartOutline outline = raps::chart_outline(chart.uv, chart.triangles);
    assert_int_equal(outline.usable, outline_usable);
    for (int draw = 0; draw < 60; ++draw) {
        // From a tenth of a cell per square (many triangles to a cell) to 12 cells per square.
        const double scale = std::exp(random.uniform(std::log(0.1), std::log(12.0)));
        const double angle = random.uniform(0.0, 6.283185307179586);
        // Some draws on the cells' grid: corners on cell borders and centres, edges along them.
        const bool aligned = draw % 4 == 0;
        const Eigen::Vector2d offset =
            aligned ? Eigen::Vector2d(100.5, 100.0)
                    : Eigen::Vector2d(random.uniform(60.0, 140.0), random.uniform(60.0, 140.0));
        const std::vector<Eigen::Vector2d> points = placed(
            chart, aligned ? 0.0 : angle, aligned ? std::round(scale * 2) / 2 : scale, offset);
        raps::BitImage triangles, from_outline;
        triangles.resize(200, 200);
        from_outline.resize(200, 200);
        raps::rasterise(points, chart.triangles, triangles);
        raps::rasterise_chart(points, chart.triangles, outline, from_outline);
        if (triangles.bits != from_outline.bits) fail_msg("draw %d: the rasters differ", draw);
    }
}

void disks_have_the_cells_of_their_triangles(void** state) {
    (void)state;
    Random random{0x5eed};
    for (int k = 0; k < 6; ++k) {
        expect_same_cells(grid(1 + k * 3, 1 + k * 2, 0.0, random), random, true);
        expect_same_cells(grid(2 + k * 3, 3 + k, 0.3, random), random, true);
    }
    // Long and thin: one row of squares.
    expect_same_cells(grid(40, 1, 0.0, random), random, true);
}

void charts_with_holes_and_notches_have_the_cells_of_their_triangles(void** state) {
    (void)state;
    Random random{0x1234};
    // A ring: the outline has an inner loop turning the other way.
    expect_same_cells(
        grid(8, 8, 0.2, random, [](int i, int j) { return i >= 3 && i < 5 && j >= 2 && j < 6; }),
        random, true);
    // A comb: notches from one side.
    expect_same_cells(grid(9, 6, 0.2, random, [](int i, int j) { return i % 2 == 1 && j >= 2; }),
                      random, true);
    // Two parts meeting at one corner.
    expect_same_cells(grid(4, 4, 0.0, random, [](int i, int j) { return (i < 2) != (j < 2); }),
                      random, true);
}

void degenerate_triangles_have_the_cells_of_their_triangles(void** state) {
    (void)state;
    Random random{0xd06};
    Chart chart = grid(5, 4, 0.2, random);
    // A needle sticking out of the outline: a zero-area triangle on a boundary edge's line.
    const int32_t tip = static_cast<int32_t>(chart.uv.size());
    chart.uv.emplace_back(7.5, 0.0);         // beyond the bottom right corner (5, 0), along y = 0
    chart.triangles.push_back({5, 4, tip});  // along the edge (4, 0)-(5, 0), turned against it
    expect_same_cells(chart, random, true);
}

void folded_charts_are_rasterised_by_their_triangles(void** state) {
    (void)state;
    Random random{0xf01d};
    // A strip folded back over itself: its last squares turned over onto the first ones, where
    // the outline's winding cancels though the triangles cover the cells.
    Chart chart = grid(6, 2, 0.0, random);
    for (Eigen::Vector2d& p : chart.uv) {
        if (p.x() > 3.0) p.x() = 6.0 - p.x() - 0.37;
    }
    expect_same_cells(chart, random, false);
    // An edge of three triangles.
    Chart fan;
    fan.uv = {{0, 0}, {1, 0}, {0.5, 1}, {0.5, -1}, {1.5, 0.5}};
    fan.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    expect_same_cells(fan, random, false);
}

}  // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disks_have_the_cells_of_their_triangles),
        cmocka_unit_test(charts_with_holes_and_notches_have_the_cells_of_their_triangles),
        cmocka_unit_test(degenerate_triangles_have_the_cells_of_their_triangles),
        cmocka_unit_test(folded_charts_are_rasterised_by_their_triangles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
