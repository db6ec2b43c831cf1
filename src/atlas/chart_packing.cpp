#include "atlas/chart_packing.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "atlas/chart_raster.h"
#include "atlas/skyline_packing.h"
#include "core/error.h"
#include "core/portable_math.h"

namespace raps {
namespace {

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

// A layout whose square is smaller than this fraction of the resolution is packed again at the
// density that fills it (ChartPacker::refit).
constexpr double kRefitBelow = 0.97;

// A way to turn a chart before its quarter turns: the rotation (cos, sin) and the turned
// chart's box, its lower corner and size in uv units.
struct Orientation {
    Eigen::Vector2d rotation, origin, extent;
};

Orientation orientation_of(const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& r) {
    const TurnedBox box = turned_box(uv, r);
    return {r, box.origin, box.extent};
}

// With any rotation allowed, the 32 largest charts may also be placed turned by 15, 30, 45, 60
// and 75 degrees from their smallest box (each in four quarter turns): an organic chart's
// outline meets its neighbours' in more ways, and the search keeps the way that lands lowest.
// Small charts fill holes whichever way they are turned; they keep four turns, which bounds
// the search for thousands of charts. Measured (docs/bench-scene.md): with the finer hole
// filling of skyline_packing.cpp, the ten-mesh scene of issue 23 0.691 -> 0.720, the mean of
// the 16 shared meshes alone 0.682 -> 0.702; 4 ways instead of 6, or 16 charts instead of 32,
// gave 0.70 to 0.71 on the scene.
constexpr int kOrientations = 6;
constexpr size_t kTurnedCharts = 32;

// A chart layout: each chart's lower left cell and its placement index (PreparedChart).
struct Layout {
    std::vector<Eigen::Vector2i> at;
    std::vector<int> quarter;
    int32_t width = 0, height = 0;
    int64_t cost() const { return layout_cost(width, height); }
};

// One trial of the layout search: an order, a strip width and a scoring rule.
struct Trial {
    size_t order;
    int32_t width;
    bool count_waste;
    int turn_limit;  // kAllTurns, or 4: each chart turned its first way only
};

// The layout search's answer: the cheapest layout, its trial and the order it packed.
struct Found {
    Layout layout;
    Trial trial;
    std::vector<size_t> order;
};

constexpr int64_t kUnbeaten = std::numeric_limits<int64_t>::max();

// pack_charts, step by step: turn the charts, fit the density to the resolution, search the
// layouts at that density, and place the uvs.
class ChartPacker {
  public:
    ChartPacker(const std::vector<PackInput>& charts, const PackSettings& settings,
                ThreadPool& pool, const ProgressSpan& progress)
        : charts_(charts),
          settings_(settings),
          pool_(pool),
          beat_(progress.part(0.0, 0.0)),
          count_(charts.size()),
          padding_(std::max(0, settings.padding)),
          resolution_(std::max(1, settings.resolution)),
          limit_(static_cast<int32_t>(resolution_)) {}

    PackResult run() {
        if (count_ == 0) return empty_result();
        orient();
        make_orders();
        fit_density();
        add_orientations();
        Found found;
        if (!best_layout(found)) throw no_room();
        refit(found);
        return to_uvs(found.layout);
    }

    // The density was fitted to one trial, and the cheapest layout may leave part of the square
    // empty: stretched to fill it, the padding would widen with the charts. The best trial's
    // order and rule are packed again at the density that fills the square, in strips as much
    // wider and near them. Layouts at either density are chaotic in it (a percent more density
    // can pack a tenth worse): the one whose charts are denser once stretched to the square is
    // kept.
    void refit(Found& found) {
        const int32_t side = std::max(found.layout.width, found.layout.height);
        if (count_ < 2 || side >= kRefitBelow * limit_) return;
        const double fitted = scale_, denser = 0.995 * limit_ / side;
        // Of the first density's rasters only their sizes are kept aside, which is all to_uvs
        // needs if that layout stays: their cells are freed before the second density's are
        // made, so the refit needs no more memory (fresh pages cost a fifth of the packing).
        std::vector<PreparedChart> kept = prepared_sizes();
        for (PreparedChart& chart : prepared_) {
            for (Profile& profile : chart.profiles) profile = Profile();
        }
        scale_ *= denser;
        rasterise_all(found.trial.turn_limit);
        Trial trial = found.trial;
        trial.order = 0;
        trial.width = std::clamp(static_cast<int32_t>(trial.width * denser), widest_, limit_);
        std::vector<Trial> list = {trial};
        for (double toward : {-1.0, 1.0}) {
            for (const Trial& t : near_square(trial, toward, 4)) list.push_back(t);
        }
        std::vector<Layout> packed;
        const size_t best = cheapest(list, {found.order}, packed, kUnbeaten);
        if (best < list.size() &&
            final_density(packed[best], scale_) > final_density(found.layout, fitted)) {
            found.layout = std::move(packed[best]);
            return;
        }
        scale_ = fitted;
        prepared_ = std::move(kept);
        find_widest();
    }

    // prepared_ without the profiles' cells: only their sizes.
    std::vector<PreparedChart> prepared_sizes() const {
        std::vector<PreparedChart> sizes(count_);
        for (size_t c = 0; c < count_; ++c) {
            sizes[c].rotation = prepared_[c].rotation;
            sizes[c].origin = prepared_[c].origin;
            sizes[c].turns = prepared_[c].turns;
            sizes[c].profiles.resize(prepared_[c].profiles.size());
            for (size_t k = 0; k < sizes[c].profiles.size(); ++k) {
                sizes[c].profiles[k].width = prepared_[c].profiles[k].width;
                sizes[c].profiles[k].height = prepared_[c].profiles[k].height;
            }
        }
        return sizes;
    }

    // Texels per uv unit once `layout`, packed at `scale`, is stretched to fill the square.
    double final_density(const Layout& layout, double scale) const {
        return scale * limit_ / std::max(std::max(layout.width, layout.height), 1);
    }

    // Every chart's orientations that placements below `turn_limit` use, at scale_.
    void rasterise_all(int turn_limit) {
        std::vector<std::pair<size_t, size_t>> ways;
        for (size_t c = 0; c < count_; ++c) {
            for (size_t o = 0; o < orientations_[c].size() && 4 * static_cast<int>(o) < turn_limit;
                 ++o)
                ways.emplace_back(c, o);
        }
        parallel_for_each(pool_, ways.size(), [&](size_t k) {
            beat_.report(0.0);
            profile(ways[k].first, ways[k].second, scale_);
        });
        find_widest();
    }

  private:
    PackResult empty_result() const {
        PackResult result;
        result.uv.resize(count_);
        result.page.assign(count_, 0);
        result.scaled_down.assign(count_, 0);
        result.rotation_deg.resize(count_);
        return result;
    }

    // Every chart turned to its smallest box (or not at all, by the rotation policy); the
    // largest ones also the further ways of kOrientations.
    void orient() {
        outlines_ = chart_outlines(charts_, pool_, beat_);
        orientations_.resize(count_);
        total_area_ = 0;
        for (size_t c = 0; c < count_; ++c) {
            const std::vector<Eigen::Vector2d>& uv = *charts_[c].uv;
            const Eigen::Vector2d r = settings_.rotation == ChartRotation::kAny
                                          ? charts_[c].rotation
                                          : Eigen::Vector2d(1, 0);
            orientations_[c] = {orientation_of(uv, r)};
            for (const Triangle& t : *charts_[c].triangles) {
                const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
                total_area_ += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
            }
        }
        prepared_.resize(count_);
        for (size_t c = 0; c < count_; ++c) {
            prepared_[c].rotation = orientations_[c][0].rotation;
            prepared_[c].origin = orientations_[c][0].origin;
            prepared_[c].turns = settings_.rotation == ChartRotation::kNone ? 1 : 4;
        }
    }

    const Eigen::Vector2d& extent(size_t c) const { return orientations_[c][0].extent; }

    void make_orders() {
        std::vector<Eigen::Vector2d> extents(count_);
        for (size_t c = 0; c < count_; ++c) extents[c] = extent(c);
        orders_ = size_orders(extents);
    }

    // The chart's raster in orientation `o` at `scale` texels per uv unit, padded, and its
    // four quarter turns' profiles.
    void profile(size_t c, size_t o, double scale) {
        const Orientation& way = orientations_[c][o];
        BitImage raster;
        raster.resize(static_cast<int32_t>(std::ceil(way.extent.x() * scale)) + 1 + 2 * padding_,
                      static_cast<int32_t>(std::ceil(way.extent.y() * scale)) + 1 + 2 * padding_);
        std::vector<Eigen::Vector2d> points(charts_[c].uv->size());
        for (size_t v = 0; v < points.size(); ++v) {
            points[v] = (turned(way.rotation, (*charts_[c].uv)[v]) - way.origin) * scale +
                        Eigen::Vector2d(padding_, padding_);
        }
        rasterise_chart(points, *charts_[c].triangles, outlines_[c], raster);
        for (int q = 0; q < 4; ++q) {
            BitImage turned = q < 3 ? rotate_quarter(raster) : BitImage();
            prepared_[c].profiles[4 * o + q] = make_profile(std::move(raster), padding_);
            raster = std::move(turned);
        }
    }

    // Every chart in its first orientation at `scale`; widest_ is then the narrowest strip
    // every chart fits in.
    void rasterise_first(double scale) {
        parallel_for_each(pool_, count_, [&](size_t c) {
            beat_.report(0.0);
            profile(c, 0, scale);
        });
        find_widest();
    }

    void find_widest() {
        widest_ = 1;
        for (const PreparedChart& chart : prepared_) {
            const Profile& p = chart.profiles[0];
            // A chart that may not turn needs a strip as wide as it is.
            widest_ = std::max(widest_, chart.turns == 1 ? p.width : std::min(p.width, p.height));
        }
    }

    // Each chart keeps `padding` texels on every side, however small the density makes it: a
    // few charts can need more room than the square has at any density.
    Error no_room() const {
        return Error(ErrorCode::kInvalidArgument,
                     "the " + std::to_string(count_) + " charts do not fit an atlas of " +
                         std::to_string(limit_) + " x " + std::to_string(limit_) +
                         " texels at any density with a padding of " + std::to_string(padding_) +
                         " texels around each: raise RAPS_PARAM_ATLAS_RESOLUTION or lower "
                         "RAPS_PARAM_ATLAS_PADDING");
    }

    // The side of the square as large as the charts' padded boxes together, in cells.
    int32_t square_side() const {
        double area_cells = 0;
        for (const PreparedChart& chart : prepared_)
            area_cells += static_cast<double>(chart.profiles[0].width) * chart.profiles[0].height;
        return static_cast<int32_t>(std::sqrt(area_cells));
    }

    // The strip the density is fitted in: as wide as the square of the charts' box areas (a
    // single chart: its longer side).
    int32_t density_strip() const {
        if (count_ == 1)
            return std::max(prepared_[0].profiles[0].width, prepared_[0].profiles[0].height);
        return std::clamp(square_side(), widest_, limit_);
    }

    // The density: the largest for which a skyline packing into a strip of the square's width
    // fits, found in a few steps (each scales by the room the last layout left). Pack at a
    // trial density, then raise it by the room left and pack again, so the final layout is
    // packed at (nearly) its final texel size and the padding is not inflated.
    void fit_density() {
        double scale = std::sqrt(0.45 * resolution_ * resolution_ / std::max(total_area_, 1e-300));
        double longest = 0;  // no chart may be longer than the atlas
        for (size_t c = 0; c < count_; ++c) longest = std::max(longest, extent(c).maxCoeff());
        scale = std::min(scale, (resolution_ - 2.0 * padding_ - 2.0) / std::max(longest, 1e-300));
        double fitted = -1;
        for (int attempt = 0; attempt < 24; ++attempt) {
            rasterise_first(scale);
            Layout layout = empty_layout();
            const bool fits = pack(orders_[0], {0, density_strip(), false, kAllTurns}, false,
                                   layout) == StripResult::kFits;
            if (!fits) {
                if (fitted > 0) break;
                scale *= 0.85;  // nothing fitted yet: lower the density
                continue;
            }
            fitted = scale;
            const double room = resolution_ / std::max(std::max(layout.width, layout.height), 1);
            if (room < 1.02 || attempt >= 3) break;
            scale *= std::min(room, 1.5) * 0.995;
        }
        if (fitted < 0) throw no_room();
        if (fitted != scale) rasterise_first(fitted);
        scale_ = fitted;
    }

    // The largest charts' further orientations, at the fitted density (the fit used the first
    // alone: its layouts only get smaller with more ways to turn).
    void add_orientations() {
        if (settings_.rotation != ChartRotation::kAny) return;
        std::vector<size_t> by_area(count_);
        std::iota(by_area.begin(), by_area.end(), 0);
        std::stable_sort(by_area.begin(), by_area.end(),
                         [&](size_t a, size_t b) { return extent(a).prod() > extent(b).prod(); });
        by_area.resize(std::min(count_, kTurnedCharts));
        any_turned_ = !by_area.empty();
        for (size_t c : by_area) {
            const Eigen::Vector2d r0 = orientations_[c][0].rotation;
            for (int k = 1; k < kOrientations; ++k) {
                // Turned clockwise by r0, then by k quarters of a quarter turn more.
                const double a = k * (M_PI / 2) / kOrientations;
                const Eigen::Vector2d r(r0.x() * portable::cos(a) - r0.y() * portable::sin(a),
                                        r0.y() * portable::cos(a) + r0.x() * portable::sin(a));
                orientations_[c].push_back(orientation_of(*charts_[c].uv, r));
            }
            prepared_[c].profiles.resize(4 * orientations_[c].size());
            prepared_[c].turns = static_cast<int>(prepared_[c].profiles.size());
        }
        const size_t total = by_area.size() * (kOrientations - 1);
        parallel_for_each(pool_, total, [&](size_t k) {
            beat_.report(0.0);
            profile(by_area[k / (kOrientations - 1)], 1 + k % (kOrientations - 1), scale_);
        });
    }

    Layout empty_layout() const {
        Layout layout;
        layout.at.resize(count_);
        layout.quarter.resize(count_);
        return layout;
    }

    StripResult pack(const std::vector<size_t>& order, const Trial& trial, bool holes,
                     Layout& layout, const std::atomic<int64_t>* beaten_above = nullptr) const {
        layout = empty_layout();
        return pack_strip(prepared_, order, trial.width, trial.count_waste, holes, limit_,
                          layout.at, layout.quarter, layout.width, layout.height, trial.turn_limit,
                          beaten_above);
    }

    // Every order, strip width and scoring rule.
    // `density_strip` is among the widths: its skyline packing is the one the density was
    // fitted to, so some trial always fits. Strip widths are geometrically spaced from 0.83 to
    // 1.39 times the square's side (k = 2 .. 8 of a series from 0.7 to 1.8). The density is
    // fitted to the square strip, so narrower strips grow too tall: 0.7 and 0.76 fitted none of
    // the 16 shared meshes; a wider strip's layout is wider than the square the best ones need.
    std::vector<Trial> trials() const {
        std::vector<int32_t> widths = {density_strip()};
        const int32_t square = square_side();
        for (int k = 2; k <= 8 && count_ > 1; ++k) {
            const double f = 0.7 * portable::pow(1.8 / 0.7, k / 11.0);
            widths.push_back(std::clamp(static_cast<int32_t>(square * f), widest_, limit_));
        }
        std::sort(widths.begin(), widths.end());
        widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
        std::vector<Trial> list;
        for (int limit : {kAllTurns, 4}) {
            if (limit == 4 && !any_turned_) continue;
            for (size_t o = 0; o < orders_.size(); ++o) {
                for (int32_t w : widths) {
                    list.push_back({o, w, false, limit});
                    list.push_back({o, w, true, limit});
                }
            }
        }
        return list;
    }

    // The trials' cheapest layout (layout_cost: the smallest square, ties: the earlier trial),
    // then the best trial's strip width refined (near_square), then, up to kSwappedCharts
    // charts, its order improved by swaps. False when no trial fits the atlas.
    bool best_layout(Found& found) const {
        const std::vector<Trial> list = trials();
        std::vector<Layout> packed;
        const size_t best = cheapest(list, orders_, packed, kUnbeaten);
        if (best == list.size()) return false;
        found = {std::move(packed[best]), list[best], orders_[list[best].order]};
        // A layout wider than tall is tried in narrower strips, a taller one in wider strips.
        const double toward = found.layout.width >= found.layout.height ? -1.0 : 1.0;
        const std::vector<Trial> near = near_square(found.trial, toward, 6);
        const size_t closer = cheapest(near, orders_, packed, found.layout.cost());
        if (closer < near.size() && packed[closer].cost() < found.layout.cost()) {
            found.layout = std::move(packed[closer]);
            found.trial = near[closer];
        }
        if (count_ >= 2 && count_ <= kSwappedCharts) improve_by_swaps(found);
        return true;
    }

    // `steps` strip widths from `trial`'s toward the square's side, 1.5% apart: the trials'
    // widths are about 9% apart, which alone left up to a tenth of the square empty.
    std::vector<Trial> near_square(const Trial& trial, double toward, int steps) const {
        std::vector<Trial> list;
        if (count_ < 2) return list;
        for (int k = 1; k <= steps; ++k) {
            Trial t = trial;
            t.width = std::clamp(static_cast<int32_t>(trial.width * (1.0 + toward * 0.015 * k)),
                                 widest_, limit_);
            if (t.width != trial.width) list.push_back(t);
        }
        return list;
    }

    // Packs every trial, with holes filled (or on the skyline alone where filling holes
    // overflows the atlas), and returns the index of the cheapest that fits (list.size():
    // none). Trial t packs `orders[t.order]`; `beaten`: a cost already found elsewhere.
    size_t cheapest(const std::vector<Trial>& list, const std::vector<std::vector<size_t>>& orders,
                    std::vector<Layout>& packed, int64_t beaten) const {
        packed.assign(list.size(), Layout());
        std::vector<char> fits(list.size(), 0);
        // A trial is given up once its cost exceeds the cheapest finished so far: it cannot be
        // the cheapest.
        std::atomic<int64_t> cheapest_yet{beaten};
        // The strips nearest the square's side first: the cheapest layouts are nearly square,
        // and an early cheap layout gives up more of the rest. The layout chosen does not
        // depend on it.
        const int32_t square = square_side();
        std::vector<size_t> schedule(list.size());
        std::iota(schedule.begin(), schedule.end(), 0);
        std::stable_sort(schedule.begin(), schedule.end(), [&](size_t a, size_t b) {
            return std::abs(list[a].width - square) < std::abs(list[b].width - square);
        });
        parallel_for_each(pool_, list.size(), [&](size_t i) {
            beat_.report(0.0);
            const size_t k = schedule[i];
            const Trial& t = list[k];
            StripResult result = pack(orders[t.order], t, true, packed[k], &cheapest_yet);
            if (result == StripResult::kTooLarge)
                result = pack(orders[t.order], t, false, packed[k], &cheapest_yet);
            fits[k] = result == StripResult::kFits;
            if (fits[k]) lower_to(cheapest_yet, packed[k].cost());
        });
        size_t best = list.size();
        for (size_t k = 0; k < list.size(); ++k) {
            if (fits[k] && (best == list.size() || packed[k].cost() < packed[best].cost()))
                best = k;
        }
        return best;
    }

    static void lower_to(std::atomic<int64_t>& bound, int64_t value) {
        int64_t now = bound.load();
        while (value < now && !bound.compare_exchange_weak(now, value)) {
        }
    }

    // Up to kSwappedCharts charts, the best layout's chart order is then improved by swaps.
    void improve_by_swaps(Found& found) const {
        Layout& layout = found.layout;
        const Trial& trial = found.trial;
        std::vector<size_t>& kept_order = found.order;
        for (int round = 0; round < kSwapRounds; ++round) {
            std::vector<std::vector<size_t>> variants;
            for (size_t i = 0; i < count_; ++i) {
                for (size_t j = i + 1; j < count_; ++j) {
                    variants.push_back(kept_order);
                    std::swap(variants.back()[i], variants.back()[j]);
                }
            }
            std::vector<Layout> tried(variants.size());
            std::vector<char> tried_fits(variants.size(), 0);
            // Only a smaller layout is kept: a variant is given up once it is as large as the
            // kept one or larger than a smaller one found.
            std::atomic<int64_t> bound{layout.cost() - 1};
            parallel_for_each(pool_, variants.size(), [&](size_t k) {
                beat_.report(0.0);
                tried_fits[k] =
                    pack(variants[k], trial, true, tried[k], &bound) == StripResult::kFits;
                if (tried_fits[k]) lower_to(bound, tried[k].cost());
            });
            bool improved = false;
            for (size_t k = 0; k < variants.size(); ++k) {
                if (tried_fits[k] && tried[k].cost() < layout.cost()) {
                    layout = std::move(tried[k]);
                    kept_order = variants[k];
                    improved = true;
                }
            }
            if (!improved) break;
        }
    }

    // The charts' uvs in the layout, in cells (continuous): each chart turned its way, then
    // its quarter turns, which map the cell (x, y) to (h - 1 - y, x), i.e. the point (x, y) to
    // (h - y, x) for continuous coordinates.
    std::vector<Eigen::Vector2d> placed_uv(size_t c, const Layout& layout) const {
        const int q = layout.quarter[c];
        const Orientation& way = orientations_[c][q / 4];
        const Profile& p = prepared_[c].profiles[q];
        const int32_t w0 = q % 2 ? p.height : p.width;  // the unturned raster's size
        const int32_t h0 = q % 2 ? p.width : p.height;
        std::vector<Eigen::Vector2d> uv(charts_[c].uv->size());
        const int64_t count = static_cast<int64_t>(uv.size());
        for (size_t v = 0; v < uv.size(); ++v) {
            beat_.at(static_cast<int64_t>(v), count);
            Eigen::Vector2d at = (turned(way.rotation, (*charts_[c].uv)[v]) - way.origin) * scale_ +
                                 Eigen::Vector2d(padding_, padding_);
            int32_t cur_w = w0, cur_h = h0;
            for (int k = 0; k < q % 4; ++k) {
                at = Eigen::Vector2d(cur_h - at.y(), at.x());
                std::swap(cur_w, cur_h);
            }
            uv[v] = at + layout.at[c].cast<double>();
        }
        return uv;
    }

    // The padding matters between charts, not at the atlas's border: the layout is placed at
    // the page's corner and stretched uniformly until its longer side is the resolution (a
    // factor >= 1, which only widens the gaps between charts). The page is the square texture
    // of resolution x resolution texels, and uvs are texels over the resolution on both axes:
    // uv space is as isotropic as texel space, so a square texture (or any uv editor) shows
    // the charts undistorted.
    PackResult to_uvs(const Layout& layout) const {
        PackResult result = empty_result();
        Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
        for (size_t c = 0; c < count_; ++c) {
            beat_.report(0.0);
            result.uv[c] = placed_uv(c, layout);
            for (const Eigen::Vector2d& at : result.uv[c]) {
                low = low.cwiseMin(at);
                high = high.cwiseMax(at);
            }
            result.rotation_deg[c] = turn_degrees(orientations_[c][layout.quarter[c] / 4].rotation,
                                                  layout.quarter[c] % 4);
        }
        const double span = (high - low).cwiseMax(Eigen::Vector2d::Zero()).maxCoeff();
        const double grow = span > 0 ? resolution_ / span : 1.0;
        result.width = result.height = static_cast<int32_t>(resolution_);
        result.texels_per_unit = scale_ * grow;
        const double to_uv = grow / resolution_;
        for (std::vector<Eigen::Vector2d>& chart_uv : result.uv) {
            beat_.report(0.0);
            for (Eigen::Vector2d& at : chart_uv) {
                at = Eigen::Vector2d(std::min(1.0, (at.x() - low.x()) * to_uv),
                                     std::min(1.0, (at.y() - low.y()) * to_uv));
            }
        }
        return result;
    }

    const std::vector<PackInput>& charts_;
    const PackSettings& settings_;
    ThreadPool& pool_;
    // Progress: a report at the start of every chart's raster and every trial layout, on
    // whichever thread runs it (the fraction stays where the phase is: the trials' number is
    // not known in advance).
    const ProgressSpan beat_;
    const size_t count_;
    const int32_t padding_;
    const double resolution_;
    const int32_t limit_;
    std::vector<ChartOutline> outlines_;
    std::vector<std::vector<Orientation>> orientations_;  // per chart, its ways to turn
    std::vector<PreparedChart> prepared_;
    std::vector<std::vector<size_t>> orders_;
    double total_area_ = 0, scale_ = 1;
    int32_t widest_ = 1;
    bool any_turned_ = false;
};

}  // namespace

std::vector<ChartOutline> chart_outlines(const std::vector<PackInput>& charts, ThreadPool& pool,
                                         const ProgressSpan& beat) {
    std::vector<ChartOutline> outlines(charts.size());
    parallel_for_each(pool, charts.size(), [&](size_t c) {
        outlines[c] = chart_outline(*charts[c].uv, *charts[c].triangles, beat.part(0.0, 0.0));
    });
    return outlines;
}

PackResult pack_charts(const std::vector<PackInput>& charts, const PackSettings& settings,
                       ThreadPool& pool, const ProgressSpan& progress) {
    return ChartPacker(charts, settings, pool, progress).run();
}

}  // namespace raps
