#include "sphere/mobius_centring.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/fill_in_runs.h"
#include "core/portable_complex.h"
#include "core/portable_math.h"
#include "core/release_in_runs.h"
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
// The passes below report to `beat` as they go: a centring step is a few passes over the mesh,
// hundreds of milliseconds at millions of triangles.
bool folds_more(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& before,
                const std::vector<Eigen::Vector3d>& after, ThreadPool& pool,
                const ProgressSpan& beat) {
    const std::vector<Triangle>& triangles = problem.mesh.triangles;
    const int64_t n = static_cast<int64_t>(triangles.size());
    const int64_t folded = parallel_sum<int64_t>(pool, n, [&](int64_t begin, int64_t end) {
        int64_t count = 0;
        for (int64_t t = begin; t < end; ++t) {
            beat.at(t, n);
            const Triangle& v = triangles[t];
            if (orientation(after[v[0]], after[v[1]], after[v[2]]) > 0.0) continue;
            count += orientation(before[v[0]], before[v[1]], before[v[2]]) > 0.0;
        }
        return count;
    });
    return folded > 0;
}

using Complex = std::complex<double>;

// w = (a z + b) / (c z + d).
struct Mobius {
    Complex a, b, c, d;
};

Mobius compose(const Mobius& f, const Mobius& g) {  // f after g
    Mobius h{f.a * g.a + f.b * g.c, f.a * g.b + f.b * g.d, f.c * g.a + f.d * g.c,
             f.c * g.b + f.d * g.d};
    // A Moebius matrix means the same map at any scale: keep the entries near 1.
    const double big = std::max(std::max(portable::abs(h.a), portable::abs(h.b)),
                                std::max(portable::abs(h.c), portable::abs(h.d)));
    h.a /= big;
    h.b /= big;
    h.c /= big;
    h.d /= big;
    return h;
}

// Inverse stereographic projection (from the north pole) of num / den, by whichever of the
// quotient and its inverse is at most 1, so that neither infinity nor points near the north
// pole lose their relative precision.
Eigen::Vector3d lift(Complex num, Complex den) {
    if (portable::abs(num) <= portable::abs(den)) {
        const Complex w = portable::divide(num, den);
        const double r2 = std::norm(w);
        return Eigen::Vector3d(2.0 * w.real(), 2.0 * w.imag(), r2 - 1.0) / (r2 + 1.0);
    }
    const Complex v = portable::divide(den, num);
    const double v2 = std::norm(v);
    return Eigen::Vector3d(2.0 * v.real(), -2.0 * v.imag(), 1.0 - v2) / (1.0 + v2);
}

// The boost that spreads the points near the unit vector `direction` by the factor k there
// (fixed points +-direction): R^-1 diag(1, k) R with R the rotation (an SU(2) matrix in
// stereographic coordinates) that takes `direction` to the north pole.
Mobius boost_towards(const Eigen::Vector3d& direction, double k) {
    const double phi = portable::atan2(direction.y(), direction.x());
    const Complex alpha = std::sqrt(std::max(0.0, 0.5 * (1.0 + direction.z()))) *
                          Complex(portable::cos(-phi), portable::sin(-phi));
    const Complex beta = std::sqrt(std::max(0.0, 0.5 * (1.0 - direction.z())));
    const Mobius rotation{alpha, beta, -std::conj(beta), std::conj(alpha)};
    const Mobius back{std::conj(alpha), -beta, std::conj(beta), alpha};
    return compose(back, compose(Mobius{1.0, 0.0, 0.0, k}, rotation));
}

void lift_all(const std::vector<Eigen::Vector2d>& plane, int32_t pole, const Mobius& m,
              std::vector<Eigen::Vector3d>& points, ThreadPool& pool, const ProgressSpan& beat) {
    const int64_t n = static_cast<int64_t>(plane.size());
    parallel_for(pool, n, [&](int64_t begin, int64_t end) {
        for (int64_t i = begin; i < end; ++i) {
            beat.at(i, n);
            const Complex z(plane[i].x(), plane[i].y());
            points[i] = i == pole ? lift(m.a, m.c) : lift(m.a * z + m.b, m.c * z + m.d);
        }
    });
}

}  // namespace

Eigen::Vector3d mobius_boost(const Eigen::Vector3d& u, const Eigen::Vector3d& a) {
    const Eigen::Vector3d d = u - a;
    const double d2 = d.squaredNorm();
    const Eigen::Vector3d image = ((1.0 - a.squaredNorm()) * d - d2 * a) / d2;
    return image.normalized();  // |image| = 1 in exact arithmetic; renormalise the rounding
}

Eigen::Vector3d centre_of_mass(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& u,
                               ThreadPool& pool, const ProgressSpan& beat) {
    const int64_t n = static_cast<int64_t>(u.size());
    const Sum3 sum = parallel_sum<Sum3>(pool, n, [&](int64_t begin, int64_t end) {
        Sum3 s;
        for (int64_t i = begin; i < end; ++i) {
            beat.at(i, n);
            s.x += problem.mass[i] * u[i].x();
            s.y += problem.mass[i] * u[i].y();
            s.z += problem.mass[i] * u[i].z();
        }
        return s;
    });
    return Eigen::Vector3d(sum.x, sum.y, sum.z);
}

double centring_step(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u,
                     std::vector<Eigen::Vector3d>& scratch, ThreadPool& pool, bool* moved,
                     const ProgressSpan& beat) {
    if (moved) *moved = false;
    const Eigen::Vector3d centre = centre_of_mass(problem, u, pool, beat);
    const double offset = centre.norm();
    if (!(offset > 0.0)) return 0.0;
    Eigen::Vector3d a = 0.75 * centre;
    if (a.norm() > 0.9) a *= 0.9 / a.norm();
    // Fresh pages touched in runs (68 MB at 5.65M triangles: 78 ms in one go).
    if (scratch.size() != u.size())
        assign_in_runs(scratch, u.size(), Eigen::Vector3d::Zero().eval(), beat);
    for (int attempt = 0; attempt < 4; ++attempt, a *= 0.25) {
        const int64_t n = static_cast<int64_t>(u.size());
        parallel_for(pool, n, [&](int64_t begin, int64_t end) {
            for (int64_t i = begin; i < end; ++i) {
                beat.at(i, n);
                scratch[i] = mobius_boost(u[i], a);
            }
        });
        if (!folds_more(problem, u, scratch, pool, beat)) {
            u.swap(scratch);
            if (moved) *moved = true;
            break;
        }
    }
    return offset;
}

std::vector<Eigen::Vector3d> mobius_centred_lift(const SphereProblem& problem,
                                                 const std::vector<Eigen::Vector2d>& plane,
                                                 int32_t pole, double scale, ThreadPool& pool,
                                                 double tolerance, int max_steps,
                                                 const ProgressSpan& progress) {
    Mobius m{scale, 0.0, 0.0, 1.0};
    std::vector<Eigen::Vector3d> points =
        filled_in_runs(plane.size(), Eigen::Vector3d::Zero().eval(), progress.part(0.0, 0.0));
    lift_all(plane, pole, m, points, pool, progress.part(0.0, 0.0));
    for (int step = 0; step < max_steps; ++step) {
        const double done = static_cast<double>(step) / max_steps;
        const ProgressSpan beat = progress.part(done, done);
        const Eigen::Vector3d centre = centre_of_mass(problem, points, pool, beat);
        const double offset = centre.norm();
        if (!(offset > tolerance)) break;
        // As centring_step: a = 3/4 of the centre of mass, at most 0.9 long; T_a spreads the
        // points near a / |a| by (1 + |a|) / (1 - |a|).
        const double t = std::min(0.75 * offset, 0.9);
        m = compose(boost_towards(centre / offset, (1.0 + t) / (1.0 - t)), m);
        lift_all(plane, pole, m, points, pool, beat);
        progress.report(static_cast<double>(step + 1) / max_steps);
    }
    return points;
}

int mobius_centre(const SphereProblem& problem, std::vector<Eigen::Vector3d>& u, ThreadPool& pool,
                  double tolerance, int max_steps, const ProgressSpan& progress) {
    std::vector<Eigen::Vector3d> scratch;
    int steps = 0;
    bool moved = true;
    while (steps < max_steps && moved &&
           centring_step(problem, u, scratch, pool, &moved,
                         progress.part(static_cast<double>(steps) / max_steps,
                                       static_cast<double>(steps) / max_steps)) > tolerance) {
        ++steps;
        progress.report(static_cast<double>(steps) / max_steps);
    }
    release_in_runs(scratch, progress.part(1.0, 1.0));
    return steps;
}

}  // namespace raps
