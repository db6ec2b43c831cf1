#include "sphere/spherical_geometry.h"

namespace raps {

void SphericalMapGeometry::edges(int32_t a, int32_t b, int32_t c, Eigen::Vector2d* ab,
                                 Eigen::Vector2d* ac) const {
    const Eigen::Vector3d e1 = u_[b] - u_[a], e2 = u_[c] - u_[a];
    // Frame: x along e1, normal pointing away from the origin (the outward side of the
    // sphere), y = normal x x. A flipped triangle then gets a negative 2D orientation.
    const Eigen::Vector3d outward = (u_[a] + u_[b] + u_[c]).normalized();
    const double length = e1.norm();
    if (!(length > 0.0)) {
        *ab = Eigen::Vector2d::Zero();
        *ac = Eigen::Vector2d::Zero();
        return;
    }
    const Eigen::Vector3d x = e1 / length;
    const Eigen::Vector3d y = outward.cross(x).normalized();
    Eigen::Vector2d p(length, 0.0), q(e2.dot(x), e2.dot(y));
    const double flat = 0.5 * std::abs(p.x() * q.y());
    const double spherical = std::abs(area(a, b, c));
    const double scale = flat > 0.0 ? std::sqrt(spherical / flat) : 1.0;
    *ab = scale * p;
    *ac = scale * q;
}

}  // namespace raps
