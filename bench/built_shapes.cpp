#include "built_shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace raps_bench {
namespace {

// Reverses every triangle if the signed volume is negative (counter-clockwise seen from outside).
void orient_outwards(const std::vector<double>& p, std::vector<uint32_t>& triangles) {
    double volume = 0.0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const double* a = &p[3 * triangles[t]];
        const double* b = &p[3 * triangles[t + 1]];
        const double* c = &p[3 * triangles[t + 2]];
        volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    if (volume >= 0.0) return;
    for (size_t t = 0; t < triangles.size(); t += 3) std::swap(triangles[t + 1], triangles[t + 2]);
}

// profile(s) = (rho, z) for s in [0, 1], rho = 0 at both ends.
using Profile = std::function<void(double, double&, double&)>;

void build_revolution(const Profile& profile, int sectors, double min_rho,
                      std::vector<double>& positions, std::vector<uint32_t>& triangles) {
    constexpr int kSamples = 20000;
    std::vector<double> arc(kSamples + 1, 0.0);
    double rho = 0, z = 0, previous_rho = 0, previous_z = 0;
    profile(0.0, previous_rho, previous_z);
    for (int k = 1; k <= kSamples; ++k) {
        profile(static_cast<double>(k) / kSamples, rho, z);
        arc[k] = arc[k - 1] + std::hypot(rho - previous_rho, z - previous_z);
        previous_rho = rho;
        previous_z = z;
    }
    positions.clear();
    triangles.clear();
    const auto add = [&](double x, double y, double w) {
        positions.insert(positions.end(), {x, y, w});
        return static_cast<uint32_t>(positions.size() / 3 - 1);
    };
    profile(0.0, rho, z);
    const uint32_t north = add(0.0, 0.0, z);
    int rings = 0, k = 0;
    double at = 0.0;
    for (;;) {
        profile(static_cast<double>(k) / kSamples, rho, z);
        at += 2.0 * M_PI * std::max(rho, min_rho) / sectors;
        while (k < kSamples && arc[k] < at) ++k;
        if (k >= kSamples || arc[kSamples] - at < 0.5 * 2.0 * M_PI * min_rho / sectors) break;
        profile(static_cast<double>(k) / kSamples, rho, z);
        const double twist = (rings % 2) * M_PI / sectors;
        for (int j = 0; j < sectors; ++j) {
            const double phi = 2.0 * M_PI * j / sectors + twist;
            add(rho * std::cos(phi), rho * std::sin(phi), z);
        }
        ++rings;
    }
    profile(1.0, rho, z);
    const uint32_t south = add(0.0, 0.0, z);
    const uint32_t n = static_cast<uint32_t>(sectors);
    const auto triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
        triangles.insert(triangles.end(), {a, b, c});
    };
    for (uint32_t j = 0; j < n; ++j) triangle(north, 1 + j, 1 + (j + 1) % n);
    for (int r = 0; r + 1 < rings; ++r) {
        const uint32_t a = 1 + static_cast<uint32_t>(r) * n, b = a + n;
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t j1 = (j + 1) % n;
            if (r % 2 == 0) {
                triangle(a + j, b + j, a + j1);
                triangle(a + j1, b + j, b + j1);
            } else {
                triangle(a + j, b + j, b + j1);
                triangle(a + j, b + j1, a + j1);
            }
        }
    }
    const uint32_t last = 1 + static_cast<uint32_t>(rings - 1) * n;
    for (uint32_t j = 0; j < n; ++j) triangle(last + (j + 1) % n, last + j, south);
    orient_outwards(positions, triangles);
}

}  // namespace

void build_capsule(double aspect, int sectors, std::vector<double>& positions,
                   std::vector<uint32_t>& triangles) {
    const double h = aspect - 1.0, total = M_PI + 2.0 * h;
    const Profile profile = [&](double s, double& rho, double& z) {
        const double at = s * total;
        if (at < 0.5 * M_PI) {
            rho = std::sin(at);
            z = h + std::cos(at);
        } else if (at < 0.5 * M_PI + 2.0 * h) {
            rho = 1.0;
            z = h - (at - 0.5 * M_PI);
        } else {
            const double a = at - 0.5 * M_PI - 2.0 * h;
            rho = std::cos(a);
            z = -h - std::sin(a);
        }
    };
    build_revolution(profile, sectors, 1.0, positions, triangles);
}

void build_dumbbell(double neck, int sectors, std::vector<double>& positions,
                    std::vector<uint32_t>& triangles) {
    const double c = 1.5;
    const Profile profile = [&](double s, double& rho, double& z) {
        z = (c + 1.0) * std::cos(M_PI * s);  // denser near the poles
        const double a = 1.0 - (z - c) * (z - c), b = 1.0 - (z + c) * (z + c);
        rho = neck;
        if (a > 0.0) rho = std::max(rho, std::sqrt(a));
        if (b > 0.0) rho = std::max(rho, std::sqrt(b));
        if (s == 0.0 || s == 1.0) rho = 0.0;
    };
    build_revolution(profile, sectors, neck, positions, triangles);
}

}  // namespace raps_bench
