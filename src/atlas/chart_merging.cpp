#include "atlas/chart_merging.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <utility>

namespace raps {
namespace {

// Per chart, beside it: its 3D area and an id kept across passes.
struct Facts {
    double area;
    int64_t id;
};

struct Candidate {
    double smaller_area, length;
    int32_t a, b;
};

// Candidate pairs are tried in parallel batches of disjoint pairs and accepted in a fixed
// order, so the result does not depend on the thread count.
// A union that failed stays failed while both charts live (their maps do not change), and
// one over the L2 budget by `change` stays over it until the budget has that much room: the
// later passes skip them instead of mapping them again (lion: the last pass, which merged
// nothing, was a quarter of the atlas's time). Charts keep ids across passes for this.
// A union is judged by its adapted map: the step lowers stretch most on exactly the larger,
// more curved charts that merging makes.
class Merger {
  public:
    Merger(const AtlasSurface& surface, const std::vector<char>& seam, const Settings& settings,
           const ChartLimits& limits, double target, std::vector<AtlasChart>& charts,
           const std::vector<double>& area, const ProgressSpan& beat, ThreadPool& pool)
        : surface_(surface),
          seam_(seam),
          settings_(settings),
          limits_(limits),
          target_(target),
          charts_(charts),
          beat_(beat),
          pool_(pool) {
        for (size_t c = 0; c < charts_.size(); ++c) {
            facts_.push_back({area[c], static_cast<int64_t>(c)});
            weighted_ += term(facts_[c], charts_[c]);
        }
        next_id_ = static_cast<int64_t>(charts_.size());
    }

    // One pass over every adjacent pair; false when nothing merged.
    bool pass(const Progress& progress, double pass_start);

  private:
    static double term(const Facts& facts, const AtlasChart& chart) {
        return facts.area * chart.map.stretch_l2 * chart.map.stretch_l2;
    }
    std::pair<int64_t, int64_t> key(int32_t a, int32_t b) const {
        return {facts_[a].id, facts_[b].id};
    }
    std::vector<Candidate> candidates() const;
    std::vector<Candidate> next_batch(const std::vector<Candidate>& candidates, size_t& next) const;
    UnionLimits limits_for(const Candidate& pair) const;
    double least_change(const Candidate& pair, double predicted_l2) const;
    UnionVerdict map_union(const Candidate& pair, const UnionLimits& limits,
                           AtlasChart& chart) const;
    bool within_budget(double change) const { return weighted_ + change <= target_; }
    void decide(const Candidate& pair, AtlasChart& built, bool mapped, UnionVerdict verdict);

    const AtlasSurface& surface_;
    const std::vector<char>& seam_;
    const Settings& settings_;
    const ChartLimits& limits_;
    const double target_;
    std::vector<AtlasChart>& charts_;
    const ProgressSpan& beat_;
    ThreadPool& pool_;
    std::vector<Facts> facts_;
    double weighted_ = 0;  // sum of term() over the live charts
    int64_t next_id_ = 0;
    std::map<std::pair<int64_t, int64_t>, double> rejected_;  // id pair -> change in budget
    // Within a pass: charts merged away, and the unions made.
    std::vector<char> consumed_;
    std::vector<AtlasChart> merged_;
    std::vector<Facts> merged_facts_;
};

// Adjacent pairs with the length of the boundary they share, smallest charts first, then the
// longest shared boundary.
std::vector<Candidate> Merger::candidates() const {
    std::vector<int32_t> owner(surface_.mesh.triangles.size(), -1);
    for (size_t c = 0; c < charts_.size(); ++c) {
        for (int32_t t : charts_[c].disk.surface_triangle) owner[t] = static_cast<int32_t>(c);
    }
    std::map<std::pair<int32_t, int32_t>, double> shared;  // boundary length per pair
    for (size_t h = 0; h < surface_.twin.size(); ++h) {
        beat_.at(static_cast<int64_t>(h), static_cast<int64_t>(surface_.twin.size()));
        const int32_t o = surface_.twin[h];
        if (o < 0 || seam_[h]) continue;
        const int32_t a = owner[h / 3], b = owner[o / 3];
        if (a >= b) continue;
        const Triangle& v = surface_.mesh.triangles[h / 3];
        shared[{a, b}] +=
            (surface_.mesh.positions[v[h % 3]] - surface_.mesh.positions[v[(h % 3 + 1) % 3]])
                .norm();
    }
    std::vector<Candidate> candidates;
    for (const auto& [pair, length] : shared) {
        candidates.push_back({std::min(facts_[pair.first].area, facts_[pair.second].area), length,
                              pair.first, pair.second});
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
        if (x.smaller_area != y.smaller_area) return x.smaller_area < y.smaller_area;
        if (x.length != y.length) return x.length > y.length;
        return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
    });
    return candidates;
}

// The next batch of disjoint pairs from candidates[next...]. Pairs rejected before are in it as
// before (so the batches, hence the merges, are the same as without remembering them) but are
// not mapped again.
std::vector<Candidate> Merger::next_batch(const std::vector<Candidate>& candidates,
                                          size_t& next) const {
    std::vector<Candidate> batch;
    std::vector<char> taken(charts_.size(), 0);
    for (; next < candidates.size() && batch.size() < 64; ++next) {
        const Candidate& c = candidates[next];
        if (consumed_[c.a] || consumed_[c.b] || taken[c.a] || taken[c.b]) continue;
        taken[c.a] = taken[c.b] = 1;
        batch.push_back(c);
    }
    return batch;
}

// The least share of the predicted excess L2 stretch (squared, minus 1) that a union's final
// map keeps, as a lower bound: on the 875 unions merging mapped on the shared meshes (main
// 6532eb8, default settings) the adapted maps kept at least 0.338 of it, the free-boundary maps
// 0.9999; 0.25 leaves room. Measured only with the default adaptive step (other monitors,
// weights or strengths, or more steps, may take more away): 0 (no bound) for those.
double kept_excess(const Settings& settings) {
    if (settings.monitor == Monitor::kNone) return 0.25;
    const bool measured = settings.monitor == Monitor::kArea &&
                          settings.weights == WeightScheme::kMeanValue &&
                          settings.alpha == 1.0 && settings.iterations <= 1;
    return measured ? 0.25 : 0.0;
}

// The least change in the budget a union with this predicted free-boundary L2 can make.
double Merger::least_change(const Candidate& pair, double predicted_l2) const {
    const Facts made{facts_[pair.a].area + facts_[pair.b].area, 0};
    const double l2_squared = 1.0 + kept_excess(settings_) * (predicted_l2 * predicted_l2 - 1.0);
    return made.area * l2_squared - term(facts_[pair.a], charts_[pair.a]) -
           term(facts_[pair.b], charts_[pair.b]);
}

// The limits past which decide() rejects the union whatever the rest of its map: its box fill
// (the same test as decide's), and a predicted L2 so high that even least_change() exceeds the
// budget's room. The room is the budget's now; decide() maps a union that the room made later
// in the batch would admit.
UnionLimits Merger::limits_for(const Candidate& pair) const {
    UnionLimits limits;
    const int32_t a = pair.a, b = pair.b;
    const double union_area = facts_[a].area + facts_[b].area;
    const double parts_box =
        facts_[a].area / charts_[a].box.fill + facts_[b].area / charts_[b].box.fill;
    limits.min_fill = union_area / (parts_box / 0.9);
    const double kept = kept_excess(settings_);
    if (kept > 0) {
        const double allowed = (target_ - weighted_ + term(facts_[a], charts_[a]) +
                                term(facts_[b], charts_[b])) /
                               union_area;
        // least_change() > room exactly when l2^2 > 1 + (allowed - 1) / kept.
        const double squared = 1.0 + (allowed - 1.0) / kept;
        limits.give_up_l2 = squared > 0 ? std::sqrt(squared) : 0.0;
    }
    return limits;
}

UnionVerdict Merger::map_union(const Candidate& pair, const UnionLimits& limits,
                               AtlasChart& chart) const {
    // Every chart lists its triangles in ascending order (build_charts lists the first charts
    // so, a split keeps its chart's order, a union merges its parts'): merged, not sorted again
    // (a sort of a union of a million triangles was 100 ms without a progress call).
    const std::vector<int32_t>& a = charts_[pair.a].disk.surface_triangle;
    const std::vector<int32_t>& b = charts_[pair.b].disk.surface_triangle;
    std::vector<int32_t> triangles;
    triangles.reserve(a.size() + b.size());
    std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(triangles));
    beat_.report(0.0);
    return map_union_chart(surface_, triangles, seam_, settings_, limits_, charts_[pair.a].disk,
                           charts_[pair.b].disk, limits, chart, beat_);
}

void Merger::decide(const Candidate& pair, AtlasChart& built, bool mapped, UnionVerdict verdict) {
    const int32_t a = pair.a, b = pair.b;
    // Not mapped: rejected before, and still unless the budget now has room for it (merges with
    // a negative change can make some). Over the predicted L2: the same, with the room it was
    // mapped for. Either way it is then mapped here, against the budget as it is now.
    if (!mapped || verdict == UnionVerdict::kOverL2) {
        const double least = mapped ? least_change(pair, built.map.predicted_l2)
                                    : rejected_[key(a, b)];
        if (!within_budget(least)) {
            rejected_[key(a, b)] = least;
            return;
        }
        verdict = map_union(pair, limits_for(pair), built);
        if (verdict == UnionVerdict::kOverL2) {
            rejected_[key(a, b)] = least_change(pair, built.map.predicted_l2);
            return;
        }
    }
    // A union whose bounding box is much larger than its parts' boxes together (an arch, a
    // ring, an L) saves a chart but costs more packing space than it saves. Allowed: 1 / 0.9
    // times their area (measured with free-boundary maps by boundary first flattening: lion's
    // coverage 0.606 -> 0.687 and suzanne's 0.636 -> 0.674, against a rule of 0.8 times the
    // worse part's fill). Tested by map_union_chart (UnionLimits::min_fill) before the
    // adaptive step, which holds the boundary; that box stays the chart's.
    if (verdict != UnionVerdict::kMapped) {
        rejected_[key(a, b)] = std::numeric_limits<double>::infinity();
        return;
    }
    const double union_area = facts_[a].area + facts_[b].area;
    Facts made{union_area, 0};
    const double change =
        term(made, built) - term(facts_[a], charts_[a]) - term(facts_[b], charts_[b]);
    if (!within_budget(change)) {
        rejected_[key(a, b)] = change;
        return;
    }
    const double parts_box =
        facts_[a].area / charts_[a].box.fill + facts_[b].area / charts_[b].box.fill;
    if (union_area / built.box.fill > parts_box / 0.9) {
        rejected_[key(a, b)] = std::numeric_limits<double>::infinity();
        return;
    }
    weighted_ += change;
    consumed_[a] = consumed_[b] = 1;
    made.id = next_id_++;
    merged_.push_back(std::move(built));
    merged_facts_.push_back(made);
}

bool Merger::pass(const Progress& progress, double pass_start) {
    const std::vector<Candidate> candidates = this->candidates();
    consumed_.assign(charts_.size(), 0);
    merged_.clear();
    merged_facts_.clear();
    size_t next = 0;
    while (next < candidates.size()) {
        const std::vector<Candidate> batch = next_batch(candidates, next);
        std::vector<AtlasChart> built(batch.size());
        std::vector<UnionVerdict> verdict(batch.size(), UnionVerdict::kFailed);
        std::vector<char> mapped(batch.size(), 0);
        std::vector<size_t> union_size(batch.size());
        std::vector<UnionLimits> limits(batch.size());
        for (size_t i = 0; i < batch.size(); ++i) {
            union_size[i] = charts_[batch[i].a].disk.surface_triangle.size() +
                            charts_[batch[i].b].disk.surface_triangle.size();
            limits[i] = limits_for(batch[i]);
        }
        progress.report(Phase::kInitialMap,
                        pass_start + (1.0 - pass_start) * 0.5 * static_cast<double>(next) /
                                         static_cast<double>(candidates.size()));
        parallel_largest_first(pool_, union_size, [&](size_t i) {
            if (rejected_.count(key(batch[i].a, batch[i].b)) == 0) {
                verdict[i] = map_union(batch[i], limits[i], built[i]);
                mapped[i] = 1;
            }
            beat_.report(0.0);
        });
        for (size_t i = 0; i < batch.size(); ++i) decide(batch[i], built[i], mapped[i], verdict[i]);
    }
    if (merged_.empty()) return false;
    std::vector<AtlasChart> kept;
    std::vector<Facts> kept_facts;
    for (size_t c = 0; c < charts_.size(); ++c) {
        if (consumed_[c]) continue;
        kept.push_back(std::move(charts_[c]));
        kept_facts.push_back(facts_[c]);
    }
    for (size_t m = 0; m < merged_.size(); ++m) {
        kept.push_back(std::move(merged_[m]));
        kept_facts.push_back(merged_facts_[m]);
    }
    charts_ = std::move(kept);
    facts_ = std::move(kept_facts);
    return true;
}

}  // namespace

void merge_charts(const AtlasSurface& surface, const std::vector<char>& seam,
                  const Settings& settings, const ChartLimits& limits, double target,
                  std::vector<AtlasChart>& charts, const std::vector<double>& area,
                  const Progress& progress, double start, const ProgressSpan& beat,
                  ThreadPool& pool) {
    Merger merger(surface, seam, settings, limits, target, charts, area, beat, pool);
    for (int pass = 0; pass < 12; ++pass) {
        const double pass_start = 1.0 - (1.0 - start) * std::ldexp(1.0, -pass);
        if (!merger.pass(progress, pass_start)) break;
    }
}

}  // namespace raps
