#include "sphere/sphere_relaxation.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"
#include "core/progress.h"
#include "core/release_in_runs.h"
#include "sphere/mobius_centring.h"
#include "sphere/spherical_geometry.h"

namespace raps {
namespace {

// Weights divided by their row sum, reported to `beat` as they go (270 MB of fresh pages at
// 5.65M triangles: 85 ms without a progress call, filled in one go).
std::vector<double> normalized_rows(const VertexAdjacency& adjacency,
                                    const std::vector<double>& weights, const ProgressSpan& beat) {
    std::vector<double> normalized = filled_in_runs(weights.size(), 0.0, beat);
    const int32_t n = static_cast<int32_t>(adjacency.offsets.size()) - 1;
    for (int32_t v = 0; v < n; ++v) {
        beat.at(v, n);
        double sum = 0.0;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) sum += weights[s];
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            normalized[s] = weights[s] / sum;
        }
    }
    return normalized;
}

// det[a, b, c] of unit vectors is rounded by less than this (a few units of 2^-52, however it is
// evaluated), so above it every vertex order of the triangle gives the same sign.
constexpr double kSignCertain = 1e-13;

class Relaxer {
  public:
    Relaxer(const SphereProblem& problem, const std::vector<double>& weights,
            std::vector<Eigen::Vector3d>& u, double step, const ProgressSpan& beat)
        : problem_(problem),
          weights_(normalized_rows(problem.adjacency, weights, beat)),
          u_(u),
          step_(step) {}

    // Gives the normalised weights back in runs (release_in_runs.h) instead of in one free.
    void release(const ProgressSpan& beat) { release_in_runs(weights_, beat); }

    // Moves vertex i (refusing moves that break the plane floor when `guarded`); returns whether
    // it was refused.
    bool update(int32_t i, bool guarded) {
        const VertexAdjacency& adjacency = problem_.adjacency;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (int32_t s = adjacency.offsets[i]; s < adjacency.offsets[i + 1]; ++s) {
            mean += weights_[s] * u_[adjacency.neighbors[s]];
        }
        const Eigen::Vector3d ui = u_[i];
        const Eigen::Vector3d laplacian = mean - ui;
        Eigen::Vector3d move = step_ * (laplacian - laplacian.dot(ui) * ui);
        for (int attempt = 0; attempt < 3; ++attempt, move *= 0.5) {
            const Eigen::Vector3d candidate = (ui + move).normalized();
            if (!guarded || allowed(i, candidate)) {
                u_[i] = candidate;
                return false;
            }
        }
        return true;
    }

  private:
    // Whether moving i to `candidate` keeps every triangle of i at the plane floor (or no worse)
    // and turns none over.
    bool allowed(int32_t i, const Eigen::Vector3d& candidate) const {
        const VertexTriangles& stars = problem_.stars;
        for (int32_t e = stars.offsets[i]; e < stars.offsets[i + 1]; ++e) {
            const Eigen::Vector3d& b = u_[stars.first[e]];
            const Eigen::Vector3d& c = u_[stars.second[e]];
            const int32_t t = stars.triangle[e];
            // One normal for both tests: det = candidate . n is det[candidate, b, c], rounded
            // relative to the triangle's size (spherical_geometry.h).
            const Eigen::Vector3d n = (b - candidate).cross(c - candidate);
            const double det = candidate.dot(n);
            if (det < kSignCertain && turns_over(t, i, candidate)) return false;
            if (!above_plane_floor(det, n) && !no_worse(u_[i], candidate, b, c)) return false;
        }
        return true;
    }

    // Whether moving i to `candidate` takes triangle t from det > 0 to det <= 0 as the
    // statistics and the refusal check evaluate it: in the triangle's own vertex order. The
    // rounding of det[a, b, c] depends on the order, and for a triangle of 1e-16 of the sphere
    // the rotated order of the floor test can keep a sign the stored order loses.
    // Measured on a capsule of aspect 30: 10 triangles folded that way in the adaptive
    // relaxations, flickering from sweep to sweep.
    bool turns_over(int32_t t, int32_t i, const Eigen::Vector3d& candidate) const {
        const Triangle& v = problem_.mesh.triangles[t];
        const auto at = [&](int32_t k) -> const Eigen::Vector3d& {
            return k == i ? candidate : u_[k];
        };
        return !(orientation(at(v[0]), at(v[1]), at(v[2])) > 0.0) &&
               orientation(u_[v[0]], u_[v[1]], u_[v[2]]) > 0.0;
    }

    const SphereProblem& problem_;
    std::vector<double> weights_;
    std::vector<Eigen::Vector3d>& u_;
    double step_;
};

struct Sum9 {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Sum9& operator+=(const Sum9& o) {
        m += o.m;
        return *this;
    }
};

// Sum of |after_i - R before_i|^2 for the rotation R that fits `before` to `after` best
// (Kabsch).
double squared_move_modulo_rotation(const std::vector<Eigen::Vector3d>& after,
                                    const std::vector<Eigen::Vector3d>& before, ThreadPool& pool,
                                    const ProgressSpan& beat) {
    const int64_t n = static_cast<int64_t>(after.size());
    const Sum9 covariance = parallel_sum<Sum9>(pool, n, [&](int64_t begin, int64_t end) {
        Sum9 s;
        for (int64_t i = begin; i < end; ++i) {
            beat.at(i, n);
            s.m += after[i] * before[i].transpose();
        }
        return s;
    });
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance.m,
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) flip(2, 2) = -1.0;
    const Eigen::Matrix3d rotation = svd.matrixU() * flip * svd.matrixV().transpose();
    return parallel_sum<double>(pool, n, [&](int64_t begin, int64_t end) {
        double m = 0.0;
        for (int64_t i = begin; i < end; ++i) {
            beat.at(i, n);
            m += (after[i] - rotation * before[i]).squaredNorm();
        }
        return m;
    });
}

constexpr int64_t kMeasureEvery = 4;

// Vertices relaxed between two progress reports on all threads together (4 times as many were
// 30 ms of work at 1.8M triangles).
constexpr int64_t kVerticesPerChunk = kItemsPerReport;

}  // namespace

RelaxationReport relax_on_sphere(const SphereProblem& problem, const std::vector<double>& weights,
                                 std::vector<Eigen::Vector3d>& u, const RelaxationOptions& options,
                                 ThreadPool& pool, const ProgressSpan& progress) {
    const TriangleMesh& mesh = problem.mesh;
    const int32_t n = mesh.vertex_count();
    const double step = options.damping * (options.literal ? 1.0 : kOverRelaxation);
    // Edge length of equilateral triangles that tile the sphere with this many triangles.
    const double mean_edge =
        std::sqrt(16.0 * M_PI / (std::sqrt(3.0) * static_cast<double>(mesh.triangle_count())));
    const double unit = 1.0 / (step * mean_edge * std::sqrt(static_cast<double>(n)));
    Relaxer relaxer(problem, weights, u, step, progress.part(0.0, 0.0));
    std::vector<Eigen::Vector3d> before, scratch;
    RelaxationReport report;
    double first = 0.0, reported = 0.0;
    int64_t last_report = 0;
    progress.report(0.0);
    while (report.sweeps < options.max_sweeps) {
        // The move is measured over every kMeasureEvery-th sweep (it costs a copy and two passes).
        const bool measure = (report.sweeps + 1) % kMeasureEvery == 0 ||
                             report.sweeps + 1 == options.max_sweeps || report.sweeps == 0;
        if (measure) copy_in_runs(before, u, progress.part(reported, reported));
        // Within a sweep the fraction stays, but it is reported again every kItemsPerReport
        // vertices (a colour's vertices move independently, so cutting a colour into chunks
        // changes nothing), so that a cancel never waits for a whole sweep.
        if (options.literal) {
            for (int32_t i = 0; i < n; ++i) {
                if (i % kItemsPerReport == 0 && i > 0) progress.report(reported);
                relaxer.update(i, false);
            }
        } else {
            for (const std::vector<int32_t>& color : problem.colors) {
                const int64_t size = static_cast<int64_t>(color.size());
                for (int64_t chunk = 0; chunk < size; chunk += kVerticesPerChunk) {
                    if (chunk > 0) progress.report(reported);
                    const int64_t chunk_size = std::min(kVerticesPerChunk, size - chunk);
                    report.refused +=
                        parallel_sum<int64_t>(pool, chunk_size, [&](int64_t begin, int64_t end) {
                            int64_t refused = 0;
                            for (int64_t k = chunk + begin; k < chunk + end; ++k)
                                refused += relaxer.update(color[k], true);
                            return refused;
                        });
                }
                progress.report(reported);
            }
            centring_step(problem, u, scratch, pool, nullptr, progress.part(reported, reported));
        }
        ++report.sweeps;
        if (!measure) continue;
        report.residual = std::sqrt(squared_move_modulo_rotation(
                              u, before, pool, progress.part(reported, reported))) *
                          unit;
        if (report.sweeps == 1) first = report.residual;
        if (!(report.residual >= options.tolerance)) {  // NaN stops too
            report.converged = report.residual < options.tolerance;
            break;
        }
        // Progress: the larger of the sweeps' share and the residual's way down (log scale) to
        // the tolerance.
        const double by_sweeps =
            static_cast<double>(report.sweeps) / static_cast<double>(options.max_sweeps);
        const double by_residual =
            first > options.tolerance && report.residual < first
                ? portable::log(first / report.residual) / portable::log(first / options.tolerance)
                : 0.0;
        const double fraction = std::min(1.0, std::max(by_sweeps, by_residual));
        if (fraction >= reported + 0.01 || report.sweeps - last_report >= 16) {
            reported = std::max(reported, fraction);
            last_report = report.sweeps;
            progress.report(reported);
        }
    }
    relaxer.release(progress.part(1.0, 1.0));
    release_in_runs(before, progress.part(1.0, 1.0));
    release_in_runs(scratch, progress.part(1.0, 1.0));
    progress.report(1.0);
    return report;
}

}  // namespace raps
