#include "atlas/chart_segmentation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "atlas/huge_pages.h"
#include "core/fill_in_runs.h"
#include "core/portable_math.h"

namespace raps {
namespace {

struct Geometry {
    std::vector<Eigen::Vector3d> normal;  // unit normal per triangle
    std::vector<double> step;             // per half-edge: centroid to centroid across it
    std::vector<double> area;             // per triangle
    std::vector<char> barrier;            // per half-edge: charts may not grow across it
};

// Every triangle and half-edge on its own: on the pool, the same bits for any thread count.
// Centroids are computed where a step needs them, twice each, rather than kept: an array of
// them was a fresh 24 bytes per triangle, and pages touched for the first time were most of
// this function's time (11 of 37 ms of face.obj's segmentation measured by thread CPU time).
Geometry measure(const AtlasSurface& surface, const SegmentationSettings& settings,
                 ThreadPool& pool, const ProgressSpan& progress) {
    const TriangleMesh& mesh = surface.mesh;
    const int32_t count = mesh.triangle_count();
    Geometry g;
    // Filled in runs (fill_in_runs.h): the step lengths filled in one go were 230 ms without a
    // progress call at 3.3M triangles.
    reserve_huge_pages(g.normal, count);
    assign_in_runs(g.normal, count, Eigen::Vector3d(0, 0, 0), progress.part(0.0, 0.05));
    reserve_huge_pages(g.area, count);
    assign_in_runs(g.area, count, 0.0, progress.part(0.05, 0.1));
    parallel_for(pool, count, [&](int64_t run_begin, int64_t run_end) {
        progress.at(run_begin, count, 0.1, 0.5);
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            const Eigen::Vector3d n = (mesh.positions[v[1]] - mesh.positions[v[0]])
                                          .cross(mesh.positions[v[2]] - mesh.positions[v[0]]);
            g.area[t] = 0.5 * n.norm();
            g.normal[t] = n.normalized();
        }
    });
    auto centroid = [&](int32_t t) -> Eigen::Vector3d {
        const Triangle& v = mesh.triangles[t];
        return (mesh.positions[v[0]] + mesh.positions[v[1]] + mesh.positions[v[2]]) / 3.0;
    };
    const double hard_cosine = portable::cos(settings.hard_edge_angle_deg * M_PI / 180.0);
    reserve_huge_pages(g.barrier, 3 * static_cast<size_t>(count));
    assign_in_runs(g.barrier, 3 * static_cast<size_t>(count), {}, progress.part(0.5, 0.55));
    reserve_huge_pages(g.step, 3 * static_cast<size_t>(count));  // every grow takes every step
    assign_in_runs(g.step, 3 * static_cast<size_t>(count), 0.0, progress.part(0.55, 0.6));
    parallel_for(pool, count, [&](int64_t run_begin, int64_t run_end) {
        progress.at(run_begin, count, 0.6, 1.0);
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Eigen::Vector3d at = centroid(t);
            for (int32_t h = 3 * t; h < 3 * t + 3; ++h) {
                const int32_t o = surface.twin[h];
                g.step[h] = o >= 0 ? (centroid(o / 3) - at).norm() : 0.0;
                // A polygon's own edges are never barriers: the polygon grows as one.
                g.barrier[h] =
                    o < 0 || (settings.hard_edge_angle_deg < 180.0 && !joins_polygon(surface, h) &&
                              g.normal[t].dot(g.normal[o / 3]) < hard_cosine);
            }
        }
    });
    return g;
}

struct Candidate {
    double distance;
    int32_t triangle, chart;
};

// Candidates taken in order of (distance, triangle, chart), where no distance pushed is below
// the last one taken while any are waiting (each is a taken one plus a step across an edge): a
// radix heap (Ahuja, Mehlhorn, Orlin & Tarjan 1990) over the distance's bits, which for
// non-negative doubles order as the numbers do. Each candidate moves down a few of the 65 buckets
// instead of through the levels of a binary heap, whose mispredicted comparisons were most of the
// segmentation (2 ms per growth on cheburashka).
class CandidateQueue {
  public:
    void clear() {
        for (std::vector<Candidate>& bucket : buckets_) bucket.clear();
        last_ = 0;
        size_ = 0;
        filled_ = 0;
    }
    bool empty() const { return size_ == 0; }
    void push(const Candidate& c) {
        if (size_ == 0) last_ = 0;  // a new chart's seed starts again from distance 0
        const size_t bucket = bucket_of(key(c.distance));
        buckets_[bucket].push_back(c);
        if (bucket > 0) filled_ |= uint64_t(1) << (bucket - 1);
        ++size_;
    }
    Candidate pop() {
        if (buckets_[0].empty()) {
            // The lowest non-empty bucket holds the next distance: it becomes the last, and
            // the bucket's candidates fall into lower buckets relative to it.
            const size_t i = 1 + __builtin_ctzll(filled_);
            uint64_t lowest = key(buckets_[i][0].distance);
            for (const Candidate& c : buckets_[i]) lowest = std::min(lowest, key(c.distance));
            last_ = lowest;
            for (const Candidate& c : buckets_[i]) {
                const size_t bucket = bucket_of(key(c.distance));
                buckets_[bucket].push_back(c);
                if (bucket > 0) filled_ |= uint64_t(1) << (bucket - 1);
            }
            buckets_[i].clear();
            filled_ &= ~(uint64_t(1) << (i - 1));
        }
        // Bucket 0 holds the candidates at exactly the last distance (usually one).
        std::vector<Candidate>& ties = buckets_[0];
        size_t first = 0;
        for (size_t k = 1; k < ties.size(); ++k) {
            if (std::make_pair(ties[k].triangle, ties[k].chart) <
                std::make_pair(ties[first].triangle, ties[first].chart)) {
                first = k;
            }
        }
        const Candidate taken = ties[first];
        ties[first] = ties.back();
        ties.pop_back();
        --size_;
        return taken;
    }

  private:
    static uint64_t key(double distance) {
        uint64_t bits;
        std::memcpy(&bits, &distance, sizeof(bits));
        return bits;
    }
    size_t bucket_of(uint64_t k) const { return k == last_ ? 0 : 64 - __builtin_clzll(k ^ last_); }

    std::vector<Candidate> buckets_[65];
    uint64_t last_ = 0;
    size_t size_ = 0;
    uint64_t filled_ = 0;  // bit i - 1: bucket i (1 .. 64) holds candidates
};

class Grower {
  public:
    Grower(const AtlasSurface& surface, const Geometry& geometry,
           const SegmentationSettings& settings)
        : surface_(surface),
          g_(geometry),
          min_cosine_(portable::cos(settings.max_normal_deviation_deg * M_PI / 180.0)) {}

    // Grows charts from `seeds` until every triangle has one (adding seeds where none can grow),
    // reporting the share of triangles assigned every kItemsPerReport of them.
    std::vector<int32_t> grow(std::vector<int32_t> seeds, const ProgressSpan& progress) {
        const int32_t count = surface_.mesh.triangle_count();
        progress_ = progress;
        assigned_ = 0;
        assign_in_runs(chart_, static_cast<size_t>(count), -1, progress.part(0.0, 0.0));
        charts_.clear();
        queue_.clear();
        for (int32_t seed : seeds) start_chart(seed);
        int32_t next_unassigned = 0;
        for (;;) {
            drain();
            while (next_unassigned < count && chart_[next_unassigned] >= 0) ++next_unassigned;
            if (next_unassigned == count) break;
            start_chart(next_unassigned);
        }
        return chart_;
    }

    // The triangle of each chart farthest (in hops) from the chart's boundary: its centre.
    std::vector<int32_t> centres(const std::vector<int32_t>& chart,
                                 const ProgressSpan& progress) const {
        const int32_t count = surface_.mesh.triangle_count();
        const int32_t chart_count = *std::max_element(chart.begin(), chart.end()) + 1;
        progress.report(0.0);
        // Reserved whole (with huge pages): a frontier doubled through ever larger copies was
        // a third of this search's time in fresh pages. Not kept from one iteration to the
        // next: held through the growths, they pushed the heap's top up by their size, which
        // stayed resident through the chart maps (the peak).
        std::vector<int32_t> depth, frontier;
        reserve_huge_pages(depth, count);
        reserve_huge_pages(frontier, count);
        assign_in_runs(depth, static_cast<size_t>(count), -1, progress.part(0.0, 0.0));
        for (int32_t t = 0; t < count; ++t) {
            progress.at(t, count, 0.0, 0.4);
            for (int k = 0; k < 3; ++k) {
                const int32_t o = surface_.twin[3 * t + k];
                if (o < 0 || chart[o / 3] != chart[t] || g_.barrier[3 * t + k]) {
                    depth[t] = 0;
                    frontier.push_back(t);
                    break;
                }
            }
        }
        for (size_t i = 0; i < frontier.size(); ++i) {
            progress.at(static_cast<int64_t>(i), count, 0.4, 0.9);
            const int32_t t = frontier[i];
            for (int k = 0; k < 3; ++k) {
                const int32_t o = surface_.twin[3 * t + k];
                if (o >= 0 && !g_.barrier[3 * t + k] && chart[o / 3] == chart[t] &&
                    depth[o / 3] < 0) {
                    depth[o / 3] = depth[t] + 1;
                    frontier.push_back(o / 3);
                }
            }
        }
        std::vector<int32_t> best(chart_count, -1);
        for (int32_t t = 0; t < count; ++t) {
            progress.at(t, count, 0.9, 1.0);
            const int32_t c = chart[t];
            if (best[c] < 0 || depth[t] > depth[best[c]]) best[c] = t;
        }
        return best;
    }

  private:
    struct Chart {
        Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    };

    void start_chart(int32_t seed) {
        const int32_t c = static_cast<int32_t>(charts_.size());
        charts_.emplace_back();
        if (chart_[seed] >= 0) return;  // an empty chart; renumbered away later
        assign(seed, c, 0.0);
    }

    // Assigns `first` and the rest of its input polygon (across the polygon's own edges, which
    // are never a chart boundary: a polygon is one unit of growth).
    void assign(int32_t first, int32_t c, double distance) {
        chart_[first] = c;
        polygon_.assign(1, first);
        Chart& chart = charts_[c];
        while (!polygon_.empty()) {
            const int32_t t = polygon_.back();
            polygon_.pop_back();
            progress_.at(++assigned_, surface_.mesh.triangle_count());
            chart.normal_sum += g_.area[t] * g_.normal[t];
            for (int k = 0; k < 3; ++k) {
                const int32_t o = surface_.twin[3 * t + k];
                if (o < 0 || g_.barrier[3 * t + k] || chart_[o / 3] >= 0) continue;
                if (joins_polygon(surface_, 3 * t + k)) {
                    chart_[o / 3] = c;
                    polygon_.push_back(o / 3);
                } else {
                    // Its normal is read when it is taken, its area, twins and steps when it
                    // is assigned: loaded now, they are in cache by then.
                    __builtin_prefetch(&g_.normal[o / 3]);
                    __builtin_prefetch(&g_.area[o / 3]);
                    __builtin_prefetch(&surface_.twin[o - o % 3]);
                    __builtin_prefetch(&g_.step[o - o % 3]);
                    queue_.push({distance + g_.step[3 * t + k], o / 3, c});
                }
            }
        }
    }

    bool accepts(int32_t t, int32_t c) const {
        return g_.normal[t].dot(charts_[c].normal_sum.normalized()) >= min_cosine_;
    }

    void drain() {
        while (!queue_.empty()) {
            const Candidate next = queue_.pop();
            if (chart_[next.triangle] >= 0) continue;
            if (accepts(next.triangle, next.chart))
                assign(next.triangle, next.chart, next.distance);
        }
    }

    const AtlasSurface& surface_;
    const Geometry& g_;
    const double min_cosine_;
    std::vector<int32_t> chart_;
    std::vector<Chart> charts_;
    CandidateQueue queue_;
    std::vector<int32_t> polygon_;  // triangles of the polygon being assigned
    ProgressSpan progress_;
    int64_t assigned_ = 0;
};

// Renumbers charts 0.. in order of their first triangle, dropping empty ids.
std::vector<int32_t> compact_ids(std::vector<int32_t> chart, const ProgressSpan& beat) {
    std::vector<int32_t> renamed;
    const int32_t max_id = chart.empty() ? -1 : *std::max_element(chart.begin(), chart.end());
    beat.report(0.0);
    renamed.assign(max_id + 1, -1);
    int32_t next = 0;
    beat.in_runs(static_cast<int64_t>(chart.size()), [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            int32_t& c = chart[i];
            if (renamed[c] < 0) renamed[c] = next++;
            c = renamed[c];
        }
    });
    return chart;
}

}  // namespace

namespace {

// Region growing over triangles leaves saw-tooth boundaries (single triangles poking into the
// neighbour, most visibly on triangulated quad meshes); they lengthen seams and waste packing
// space. A triangle whose two uncut neighbours share another chart joins it; a few sweeps in
// index order remove the teeth (the order makes it deterministic). slot(i): the i-th triangle
// visited, as an index into `chart`; across(t, k): the triangle across side k of t, or -1;
// pinned(t): t is part of a polygon and never moves alone.
template <typename Slot, typename Across, typename Pinned>
void smooth_sweeps(int64_t count, const Slot& slot, const Across& across, const Pinned& pinned,
                   std::vector<int32_t>& chart, const ProgressSpan& progress) {
    for (int sweep = 0; sweep < 4; ++sweep) {
        bool changed = false;
        progress.part(sweep / 4.0, (sweep + 1) / 4.0)
            .in_runs(count, [&](int64_t run_begin, int64_t run_end) {
                for (int64_t i = run_begin; i < run_end; ++i) {
                    const int32_t t = slot(i);
                    // A triangle of a polygon moves only with it: the teeth are triangles.
                    if (pinned(t)) continue;
                    int32_t other[3], found = 0;
                    for (int k = 0; k < 3; ++k) {
                        const int32_t o = across(t, k);
                        if (o >= 0 && chart[o] != chart[t]) other[found++] = chart[o];
                    }
                    int32_t winner = -1;
                    if (found >= 2 && other[0] == other[1]) winner = other[0];
                    if (found == 3 && (other[0] == other[2] || other[1] == other[2]))
                        winner = other[2];
                    if (winner >= 0) {
                        chart[t] = winner;
                        changed = true;
                    }
                }
            });
        if (!changed) break;
    }
}

}  // namespace

void smooth_chart_boundaries(const AtlasSurface& surface, const std::vector<char>& barrier,
                             const std::vector<int32_t>& triangles, std::vector<int32_t>& chart,
                             const ProgressSpan& progress) {
    smooth_sweeps(
        static_cast<int64_t>(triangles.size()), [&](int64_t i) { return triangles[i]; },
        [&](int32_t t, int k) {
            const int32_t o = surface.twin[3 * t + k];
            return o >= 0 && !barrier[3 * t + k] ? o / 3 : -1;
        },
        [&](int32_t t) {
            return joins_polygon(surface, 3 * t) || joins_polygon(surface, 3 * t + 1) ||
                   joins_polygon(surface, 3 * t + 2);
        },
        chart, progress);
}

void smooth_chart_boundaries(const std::vector<int32_t>& neighbour, std::vector<int32_t>& chart,
                             const ProgressSpan& progress, const std::vector<char>& pinned) {
    smooth_sweeps(
        static_cast<int64_t>(chart.size()), [](int64_t i) { return static_cast<int32_t>(i); },
        [&](int32_t t, int k) { return neighbour[3 * t + k]; },
        [&](int32_t t) { return !pinned.empty() && pinned[t]; }, chart, progress);
}

std::vector<int32_t> segment_charts(const AtlasSurface& surface,
                                    const SegmentationSettings& settings, ThreadPool& pool,
                                    const ProgressSpan& progress) {
    if (surface.mesh.triangles.empty()) return {};
    // Progress: the geometry, then each growth (the first and one per Lloyd iteration, with the
    // centres before it) an equal share, then the smoothing.
    const Geometry geometry = measure(surface, settings, pool, progress.part(0.0, 0.1));
    Grower grower(surface, geometry, settings);
    const double share = 0.8 / (1 + settings.lloyd_iterations);
    std::vector<int32_t> chart = compact_ids(grower.grow({0}, progress.part(0.1, 0.1 + share)),
                                             progress.part(0.1 + share, 0.1 + share));
    for (int i = 0; i < settings.lloyd_iterations; ++i) {
        const ProgressSpan iteration = progress.part(0.1 + (i + 1) * share, 0.1 + (i + 2) * share);
        const std::vector<int32_t> centres = grower.centres(chart, iteration.part(0.0, 0.2));
        std::vector<int32_t> regrown =
            compact_ids(grower.grow(centres, iteration.part(0.2, 1.0)), iteration.part(1.0, 1.0));
        // The same charts again: their centres, hence every later iteration, are the same too
        // (charts fenced in by hard edges, as on CAD parts, are there from the start).
        if (regrown == chart) break;
        chart = std::move(regrown);
    }
    std::vector<int32_t> all(chart.size());
    std::iota(all.begin(), all.end(), 0);
    smooth_chart_boundaries(surface, geometry.barrier, all, chart, progress.part(0.9, 1.0));
    return compact_ids(chart, progress.part(1.0, 1.0));
}

}  // namespace raps
