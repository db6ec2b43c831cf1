#include "sphere/gauss_map.h"

namespace raps {

std::vector<Eigen::Vector3d> gauss_map(const TriangleMesh& mesh) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& x : mesh.positions) mean += x;
    mean /= static_cast<double>(mesh.positions.size());
    std::vector<Eigen::Vector3d> u(mesh.positions.size());
    for (size_t i = 0; i < u.size(); ++i) {
        const Eigen::Vector3d d = mesh.positions[i] - mean;
        const double length = d.norm();
        u[i] = length > 0.0 ? Eigen::Vector3d(d / length) : Eigen::Vector3d::UnitZ();
    }
    return u;
}

}  // namespace raps
