// The rotation by an angle about a unit axis with the portable sine and cosine: what
// Eigen::AngleAxisd::toRotationMatrix computes (the same products in the same order), without
// its calls to the C library's sin and cos (core/portable_math.h says why).
#pragma once

#include <Eigen/Core>

#include "core/portable_math.h"

namespace raps::portable {

inline Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& unit_axis) {
    const Eigen::Vector3d sin_axis = sin(angle) * unit_axis;
    const double c = cos(angle);
    const Eigen::Vector3d cos1_axis = (1.0 - c) * unit_axis;
    Eigen::Matrix3d r;
    double t = cos1_axis.x() * unit_axis.y();
    r(0, 1) = t - sin_axis.z();
    r(1, 0) = t + sin_axis.z();
    t = cos1_axis.x() * unit_axis.z();
    r(0, 2) = t + sin_axis.y();
    r(2, 0) = t - sin_axis.y();
    t = cos1_axis.y() * unit_axis.z();
    r(1, 2) = t - sin_axis.x();
    r(2, 1) = t + sin_axis.x();
    for (int i = 0; i < 3; ++i) r(i, i) = cos1_axis[i] * unit_axis[i] + c;
    return r;
}

}  // namespace raps::portable
