#include "sphere/mobius_centring.h"

#include <algorithm>
#include <cmath>

#include "sphere/spherical_geometry.h"

namespace raps {
namespace {

struct Sum3 {
    double x = 0, y = 0, z = 0;
    Sum3& operator+=(const Sum3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
};

// Whether the map `after` turns over a triangle that `before` does not.
bool folds_more(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& before,
                const std::vector<Eigen::Vector3d>& after, ThreadPool& pool) {
    const std::vector<Triangle>& triangles = problem.mesh.triangles;
    const int64_t folded = parallel_sum<int64_t>(
        pool, static_cast<int64_t>(triangles.size()), [&](int64_t begin, int64_t end) {
            int64_t count = 0;
            for (int64_t t = begin; t < end; ++t) {
                const Triangle& v = triangles[t];
                if (orientation(after[v[0]], after[v[1]], after[v[2]]) > 0.0) continue;
                count += orientation(before[v[0]], before[v[1]], before[v[2]]) > 0.0;
            }
            return count;
        });
    return folded > 0;
}

}  // namespace

Eigen::Vector3d mobius_boost(const Eigen::Vector3d& u, const Eigen::Vector3d& a) {
    const Eigen::Vector3d d = u - a;
    const double d2 = d.squaredNorm();
    const Eigen::Vector3d image = ((1.0 - a.squaredNorm()) * d - d2 * a) / d2;
    return image.normalized();  // |image| = 1 in exact arithmetic; renormalise the rounding
}

Eigen::Vector3d centre_of_mass(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& u,
                               ThreadPool& pool) {
    const Sum3 sum =
        parallel_sum<Sum3>(pool, static_cast<int64_t>(u.size()), [&](int64_t begin, int64_t end) {
            Sum3 s;
            for (int64_t i = begin; i < end; ++i) {
                s.x += problem.mass[i] * u[i].x();
                s.y += problem.mass[i] * u[i].y();
                s.z += problem.mass[i] * u[i].z();
            }
            return s;
        });
    return Eigen::Vector3d(sum.x, sum.y, sum.z);
}

double centring_step(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u,
                     std::vector<Eigen::Vector3d>& scratch, ThreadPool& pool, bool* moved) {
    if (moved) *moved = false;
    const Eigen::Vector3d centre = centre_of_mass(problem, u, pool);
    const double offset = centre.norm();
    if (!(offset > 0.0)) return 0.0;
    Eigen::Vector3d a = 0.75 * centre;
    if (a.norm() > 0.9) a *= 0.9 / a.norm();
    scratch.resize(u.size());
    for (int attempt = 0; attempt < 2; ++attempt, a *= 0.25) {
        parallel_for(pool, static_cast<int64_t>(u.size()), [&](int64_t begin, int64_t end) {
            for (int64_t i = begin; i < end; ++i) scratch[i] = mobius_boost(u[i], a);
        });
        if (!folds_more(problem, u, scratch, pool)) {
            u.swap(scratch);
            if (moved) *moved = true;
            break;
        }
    }
    return offset;
}

int mobius_centre(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u, ThreadPool& pool,
                  double tolerance, int max_steps) {
    std::vector<Eigen::Vector3d> scratch;
    int steps = 0;
    bool moved = true;
    while (steps < max_steps && moved &&
           centring_step(problem, u, scratch, pool, &moved) > tolerance) {
        ++steps;
    }
    return steps;
}

}  // namespace raps
