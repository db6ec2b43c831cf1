#include "atlas/atlas_charts.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "atlas/chart_packing.h"
#include "atlas/chart_segmentation.h"
#include "atlas/polygon_units.h"

namespace raps {
namespace {

// Splits `triangles` in two: breadth-first from one end of the chart to find its farthest
// triangle a, from a to find b, then every triangle goes to the nearer of a and b (ties to a).
std::pair<std::vector<int32_t>, std::vector<int32_t>> split_chart(
    const AtlasSurface& surface, const std::vector<int32_t>& triangles,
    const std::vector<char>& seam, const ProgressSpan& beat) {
    std::vector<int32_t> local(surface.mesh.triangles.size(), -1);
    for (size_t i = 0; i < triangles.size(); ++i) local[triangles[i]] = static_cast<int32_t>(i);
    auto distances = [&](int32_t from) {
        std::vector<int32_t> distance(triangles.size(), -1), frontier = {from};
        distance[from] = 0;
        for (size_t i = 0; i < frontier.size(); ++i) {
            const int32_t t = triangles[frontier[i]];
            for (int k = 0; k < 3; ++k) {
                const int32_t o = surface.twin[3 * t + k];
                if (o < 0 || seam[3 * t + k] || local[o / 3] < 0 || distance[local[o / 3]] >= 0)
                    continue;
                distance[local[o / 3]] = distance[frontier[i]] + 1;
                frontier.push_back(local[o / 3]);
            }
        }
        return distance;
    };
    auto farthest = [](const std::vector<int32_t>& distance) {
        return static_cast<int32_t>(std::max_element(distance.begin(), distance.end()) -
                                    distance.begin());
    };
    const int32_t a = farthest(distances(0));
    beat.report(0.0);
    const std::vector<int32_t> from_a = distances(a);
    beat.report(0.0);
    const int32_t b = farthest(from_a);
    const std::vector<int32_t> from_b = distances(b);
    beat.report(0.0);
    std::pair<std::vector<int32_t>, std::vector<int32_t>> halves;
    // Side per surface triangle (-1: outside the chart, itself a barrier), smoothed like the
    // segmentation's boundaries so the split does not leave a saw-tooth seam.
    std::vector<int32_t> side(surface.mesh.triangles.size(), -1);
    for (size_t i = 0; i < triangles.size(); ++i) {
        // Unreached triangles (a chart in several pieces) follow a's side if not reached by b.
        const bool to_b = from_b[i] >= 0 && (from_a[i] < 0 || from_b[i] < from_a[i]);
        side[triangles[i]] = to_b ? 1 : 0;
    }
    keep_polygons_together(surface, triangles, side);
    // Only the chart's own half-edges are read: everything else stays a barrier.
    std::vector<char> barrier(seam.size(), 1);
    for (int32_t t : triangles) {
        for (int k = 0; k < 3; ++k) {
            const int32_t h = 3 * t + k, o = surface.twin[h];
            barrier[h] = seam[h] || (o >= 0 && side[o / 3] < 0);
        }
    }
    smooth_chart_boundaries(surface, barrier, triangles, side, beat);
    for (int32_t t : triangles) (side[t] == 1 ? halves.second : halves.first).push_back(t);
    if (halves.first.empty() || halves.second.empty()) {
        // One triangle or polygon, or nothing reachable: halve by polygons in their order.
        halve_by_polygons(surface, triangles, side);
        halves.first.clear();
        halves.second.clear();
        for (int32_t t : triangles) (side[t] == 1 ? halves.second : halves.first).push_back(t);
    }
    return halves;
}

// body(i) for every i on the threads, taken in order of decreasing cost (ties by index), so
// the largest charts start first and no thread is left with one big chart at the end of a
// batch. Each body writes only its own slot, so the output does not depend on the order.
void parallel_largest_first(ThreadPool& pool, const std::vector<size_t>& cost,
                            const std::function<void(size_t)>& body) {
    std::vector<size_t> order(cost.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return cost[a] > cost[b]; });
    parallel_for_each(pool, order.size(), [&](size_t k) { body(order[k]); });
}

double chart_area(const ChartDisk& disk) {
    double area = 0;
    for (const Triangle& t : disk.mesh.triangles) {
        area += 0.5 * (disk.mesh.positions[t[1]] - disk.mesh.positions[t[0]])
                          .cross(disk.mesh.positions[t[2]] - disk.mesh.positions[t[0]])
                          .norm();
    }
    return area;
}

// One chart from its triangles (those of two charts when `parts` are given): the disk and its
// adapted map, or false when it must be split. unadapted_l2: the map's L2 stretch before its
// adaptive step.
bool try_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
               const std::vector<char>& seam, const Settings& settings, const ChartLimits& limits,
               AtlasChart& chart, double& unadapted_l2, const ProgressSpan& beat,
               std::pair<const ChartDisk*, const ChartDisk*> parts = {}) {
    bool good = parts.first ? make_union_chart_disk(surface, triangles, seam, *parts.first,
                                                    *parts.second, chart.disk, beat)
                            : make_chart_disk(surface, triangles, seam, chart.disk, beat);
    if (!good && triangles.size() > 1) return false;
    beat.report(0.0);
    LaplaceSystem system = chart_laplace_system(chart.disk, beat);
    if (good) {
        chart.map = free_boundary_chart_map(chart.disk, system, limits.max_stretch_linf, beat);
        good = chart.map.injective && chart.map.stretch_linf <= limits.max_stretch_linf;
    }
    beat.report(0.0);
    // A polygon that maps badly stays whole (as a triangle does): its corners need one uv each.
    if (!good && !is_one_polygon(surface, triangles)) return false;
    if (!chart.map.injective) chart.map = circle_chart_map(chart.disk, settings, system, beat);
    unadapted_l2 = chart.map.stretch_l2;
    adapt_chart_map(chart.disk, settings, limits.max_stretch_linf, chart.map, system, beat);
    beat.report(0.0);
    chart.box =
        smallest_bounding_box(chart.map.uv, chart.disk.mesh.triangles, chart.disk.boundary_loop);
    return true;
}

}  // namespace

std::vector<AtlasChart> build_charts(const AtlasSurface& surface,
                                     const std::vector<int32_t>& chart_of,
                                     const std::vector<char>& seam, const Settings& settings,
                                     const ChartLimits& limits, const Progress& progress,
                                     ThreadPool& pool) {
    int32_t count = 0;
    for (int32_t c : chart_of) count = std::max(count, c + 1);
    std::vector<std::vector<int32_t>> pending(count);
    for (size_t t = 0; t < chart_of.size(); ++t)
        pending[chart_of[t]].push_back(static_cast<int32_t>(t));
    std::vector<AtlasChart> charts;
    // Per chart, its L2 stretch before the adaptive step: the budget below splits charts by
    // it, while merging judges by the adapted maps.
    std::vector<double> unadapted_l2;
    // Progress: the first maps by their share of the triangles to kMapped, then each merge pass
    // half of what is left, by its share of candidates. Inside a chart the work repeats the
    // fraction reached (`beat`: a span at 0, which the phase's progress never lets fall), so
    // that a cancel is seen inside the largest charts too.
    constexpr double kMapped = 0.4;
    const ProgressSpan beat(progress, Phase::kInitialMap, 0.0, 0.0);
    const double total_triangles = static_cast<double>(chart_of.size());
    double done_triangles = 0;
    // Rounds: every pending chart in parallel; the ones that fail are split into the next round.
    // Each chart's result lands in its own slot, so the outcome is the same for any thread count.
    auto process = [&](std::vector<std::vector<int32_t>> round) {
        while (!round.empty()) {
            std::vector<AtlasChart> built(round.size());
            std::vector<char> good(round.size(), 0);
            std::vector<double> built_l2(round.size(), 0.0);
            std::vector<size_t> cost(round.size());
            for (size_t i = 0; i < round.size(); ++i) cost[i] = round[i].size();
            parallel_largest_first(pool, cost, [&](size_t i) {
                good[i] = try_chart(surface, round[i], seam, settings, limits, built[i],
                                    built_l2[i], beat);
                progress.report(Phase::kInitialMap,
                                kMapped * std::min(1.0, done_triangles / total_triangles));
            });
            std::vector<std::vector<int32_t>> next;
            for (size_t i = 0; i < round.size(); ++i) {
                if (good[i]) {
                    done_triangles += static_cast<double>(round[i].size());
                    charts.push_back(std::move(built[i]));
                    unadapted_l2.push_back(built_l2[i]);
                } else {
                    auto halves = split_chart(surface, round[i], seam, beat);
                    next.push_back(std::move(halves.first));
                    next.push_back(std::move(halves.second));
                }
            }
            round = std::move(next);
        }
    };
    process(std::move(pending));
    // The L2 budget: split the largest contributor to the atlas's stretch until it meets the
    // target (or nothing splittable is left).
    std::vector<double> area(charts.size());
    double total_area = 0, weighted = 0;
    for (size_t c = 0; c < charts.size(); ++c) {
        area[c] = chart_area(charts[c].disk);
        total_area += area[c];
        weighted += area[c] * unadapted_l2[c] * unadapted_l2[c];
    }
    const double target = limits.target_stretch_l2 * limits.target_stretch_l2 * total_area;
    while (weighted > target) {
        size_t worst = charts.size();
        double worst_excess = 0;
        for (size_t c = 0; c < charts.size(); ++c) {
            const double excess = area[c] * (unadapted_l2[c] * unadapted_l2[c] - 1.0);
            if (excess > worst_excess &&
                !is_one_polygon(surface, charts[c].disk.surface_triangle)) {
                worst = c;
                worst_excess = excess;
            }
        }
        if (worst == charts.size()) break;
        const std::vector<int32_t> triangles = charts[worst].disk.surface_triangle;
        weighted -= area[worst] * unadapted_l2[worst] * unadapted_l2[worst];
        charts.erase(charts.begin() + static_cast<std::ptrdiff_t>(worst));
        area.erase(area.begin() + static_cast<std::ptrdiff_t>(worst));
        unadapted_l2.erase(unadapted_l2.begin() + static_cast<std::ptrdiff_t>(worst));
        const size_t before = charts.size();
        auto halves = split_chart(surface, triangles, seam, beat);
        process({std::move(halves.first), std::move(halves.second)});
        for (size_t c = before; c < charts.size(); ++c) {
            area.push_back(chart_area(charts[c].disk));
            weighted += area.back() * unadapted_l2[c] * unadapted_l2[c];
        }
    }
    // Merging judges the charts by their adapted maps: the budget counts what they will really
    // stretch (the free-boundary figures above overstate it).
    weighted = 0;
    for (size_t c = 0; c < charts.size(); ++c) {
        weighted += area[c] * charts[c].map.stretch_l2 * charts[c].map.stretch_l2;
    }
    // Merging: splits and the segmentation's limits leave more charts than needed. Adjacent
    // charts whose union is a valid chart are merged while the atlas's L2 stays within its
    // target, smallest charts first (they cost the most in packing and seams). Candidate pairs
    // are tried in parallel batches of disjoint pairs and accepted in a fixed order, so the
    // result does not depend on the thread count.
    // A union that failed stays failed while both charts live (their maps do not change), and
    // one over the L2 budget by `change` stays over it until the budget has that much room: the
    // later passes skip them instead of mapping them again (lion: the last pass, which merged
    // nothing, was a quarter of the atlas's time). Charts keep ids across passes for this.
    // Per chart, beside it: its 3D area and its id.
    struct Facts {
        double area;
        int64_t id;
    };
    std::vector<Facts> facts(charts.size());
    for (size_t c = 0; c < charts.size(); ++c) facts[c] = {area[c], static_cast<int64_t>(c)};
    int64_t next_id = static_cast<int64_t>(charts.size());
    constexpr double kNever = std::numeric_limits<double>::infinity();
    std::map<std::pair<int64_t, int64_t>, double> rejected;  // id pair -> change in L2 budget
    auto key = [&](int32_t a, int32_t b) { return std::make_pair(facts[a].id, facts[b].id); };
    for (int pass = 0; pass < 12; ++pass) {
        std::vector<int32_t> owner(surface.mesh.triangles.size(), -1);
        for (size_t c = 0; c < charts.size(); ++c) {
            for (int32_t t : charts[c].disk.surface_triangle) owner[t] = static_cast<int32_t>(c);
        }
        std::map<std::pair<int32_t, int32_t>, double> shared;  // boundary length per pair
        for (size_t h = 0; h < surface.twin.size(); ++h) {
            beat.at(static_cast<int64_t>(h), static_cast<int64_t>(surface.twin.size()));
            const int32_t o = surface.twin[h];
            if (o < 0 || seam[h]) continue;
            const int32_t a = owner[h / 3], b = owner[o / 3];
            if (a >= b) continue;
            const Triangle& v = surface.mesh.triangles[h / 3];
            shared[{a, b}] +=
                (surface.mesh.positions[v[h % 3]] - surface.mesh.positions[v[(h % 3 + 1) % 3]])
                    .norm();
        }
        struct Candidate {
            double smaller_area, length;
            int32_t a, b;
        };
        std::vector<Candidate> candidates;
        for (const auto& [pair, length] : shared) {
            candidates.push_back({std::min(facts[pair.first].area, facts[pair.second].area), length,
                                  pair.first, pair.second});
        }
        std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
            if (x.smaller_area != y.smaller_area) return x.smaller_area < y.smaller_area;
            if (x.length != y.length) return x.length > y.length;
            return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
        });
        std::vector<char> consumed(charts.size(), 0);
        std::vector<AtlasChart> merged_charts;
        std::vector<Facts> merged_facts;
        bool any = false;
        size_t next = 0;
        while (next < candidates.size()) {
            // A batch of disjoint pairs. Pairs rejected before are in it as before (so the
            // batches, hence the merges, are the same as without remembering them) but are not
            // mapped again.
            std::vector<Candidate> batch;
            std::vector<char> taken(charts.size(), 0);
            for (; next < candidates.size() && batch.size() < 64; ++next) {
                const Candidate& c = candidates[next];
                if (consumed[c.a] || consumed[c.b] || taken[c.a] || taken[c.b]) continue;
                taken[c.a] = taken[c.b] = 1;
                batch.push_back(c);
            }
            std::vector<AtlasChart> built(batch.size());
            std::vector<char> good(batch.size(), 0), mapped(batch.size(), 0);
            auto map_union = [&](size_t i) {
                std::vector<int32_t> triangles = charts[batch[i].a].disk.surface_triangle;
                const std::vector<int32_t>& more = charts[batch[i].b].disk.surface_triangle;
                triangles.insert(triangles.end(), more.begin(), more.end());
                std::sort(triangles.begin(), triangles.end());
                // A union is judged by its adapted map: the step lowers stretch most on exactly
                // the larger, more curved charts that merging makes.
                double unadapted;
                good[i] = try_chart(surface, triangles, seam, settings, limits, built[i], unadapted,
                                    beat, {&charts[batch[i].a].disk, &charts[batch[i].b].disk});
                mapped[i] = 1;
            };
            std::vector<size_t> union_size(batch.size());
            for (size_t i = 0; i < batch.size(); ++i) {
                union_size[i] = charts[batch[i].a].disk.surface_triangle.size() +
                                charts[batch[i].b].disk.surface_triangle.size();
            }
            const double pass_start = 1.0 - (1.0 - kMapped) * std::ldexp(1.0, -pass);
            progress.report(Phase::kInitialMap,
                            pass_start + (1.0 - pass_start) * 0.5 * static_cast<double>(next) /
                                             static_cast<double>(candidates.size()));
            parallel_largest_first(pool, union_size, [&](size_t i) {
                if (rejected.count(key(batch[i].a, batch[i].b)) == 0) map_union(i);
                beat.report(0.0);
            });
            for (size_t i = 0; i < batch.size(); ++i) {
                const int32_t a = batch[i].a, b = batch[i].b;
                if (!mapped[i]) {
                    // Still rejected unless the budget now has room for it (merges with a
                    // negative change can make some): then it is mapped after all.
                    if (weighted + rejected[key(a, b)] > target) continue;
                    map_union(i);
                }
                if (!good[i]) {
                    rejected[key(a, b)] = kNever;
                    continue;
                }
                const double union_area = facts[a].area + facts[b].area;
                const double change =
                    union_area * built[i].map.stretch_l2 * built[i].map.stretch_l2 -
                    facts[a].area * charts[a].map.stretch_l2 * charts[a].map.stretch_l2 -
                    facts[b].area * charts[b].map.stretch_l2 * charts[b].map.stretch_l2;
                if (weighted + change > target) {
                    rejected[key(a, b)] = change;
                    continue;
                }
                // A union whose bounding box is much larger than its parts' boxes together (an
                // arch, a ring, an L) saves a chart but costs more packing space than it
                // saves. Allowed: 1 / 0.9 times their area (measured with free-boundary maps by
                // boundary first flattening: lion's coverage 0.606 -> 0.687 and suzanne's
                // 0.636 -> 0.674, against a rule of 0.8 times the worse part's fill).
                const double parts_box =
                    facts[a].area / charts[a].box.fill + facts[b].area / charts[b].box.fill;
                if (union_area / built[i].box.fill > parts_box / 0.9) {
                    rejected[key(a, b)] = kNever;
                    continue;
                }
                weighted += change;
                consumed[a] = consumed[b] = 1;
                merged_charts.push_back(std::move(built[i]));
                merged_facts.push_back({union_area, next_id++});
                any = true;
            }
        }
        if (!any) break;
        std::vector<AtlasChart> kept;
        std::vector<Facts> kept_facts;
        for (size_t c = 0; c < charts.size(); ++c) {
            if (consumed[c]) continue;
            kept.push_back(std::move(charts[c]));
            kept_facts.push_back(facts[c]);
        }
        for (size_t m = 0; m < merged_charts.size(); ++m) {
            kept.push_back(std::move(merged_charts[m]));
            kept_facts.push_back(merged_facts[m]);
        }
        charts = std::move(kept);
        facts = std::move(kept_facts);
    }
    std::sort(charts.begin(), charts.end(), [](const AtlasChart& x, const AtlasChart& y) {
        return *std::min_element(x.disk.surface_triangle.begin(), x.disk.surface_triangle.end()) <
               *std::min_element(y.disk.surface_triangle.begin(), y.disk.surface_triangle.end());
    });
    return charts;
}

}  // namespace raps
