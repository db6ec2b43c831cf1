#include "solver/nested_dissection.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

namespace raps {
namespace {

// Parts no larger than this are not split further: below it the dense kernels of the
// factorization are too small for separators to pay off.
constexpr int32_t kLeafSize = 48;

class Dissection {
public:
    Dissection(const SparsePattern& pattern, const std::vector<Eigen::Vector3d>& coordinates)
        : pattern_(pattern), coordinates_(coordinates), part_(pattern.size, 0) {}

    std::vector<int32_t> run() {
        std::vector<int32_t> ids(pattern_.size);
        for (int32_t i = 0; i < pattern_.size; ++i) ids[i] = i;
        order_.reserve(pattern_.size);
        dissect(ids);
        return std::move(order_);
    }

private:
    // Orders the unknowns in ids: both halves first, then the separator between them, so that
    // eliminating either half creates no fill in the other.
    void dissect(std::vector<int32_t>& ids) {
        if (static_cast<int32_t>(ids.size()) <= kLeafSize) {
            order_.insert(order_.end(), ids.begin(), ids.end());
            return;
        }
        // Split at the median along the principal axis of the part's points: the plane through
        // the centroid that cuts the part across its longest extent, giving a short separator.
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
        for (int32_t i : ids) centroid += coordinates_[i];
        centroid /= static_cast<double>(ids.size());
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (int32_t i : ids) {
            const Eigen::Vector3d d = coordinates_[i] - centroid;
            covariance += d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
        const Eigen::Vector3d axis = eigen.eigenvectors().col(2);
        const size_t half = ids.size() / 2;
        std::nth_element(ids.begin(), ids.begin() + half, ids.end(), [&](int32_t a, int32_t b) {
            const double pa = axis.dot(coordinates_[a]), pb = axis.dot(coordinates_[b]);
            return pa < pb || (pa == pb && a < b);
        });
        const int32_t left = ++next_label_, right = ++next_label_;
        for (size_t k = 0; k < ids.size(); ++k) part_[ids[k]] = k < half ? left : right;

        // Vertex separator: the side of the cut with fewer vertices touching the other side.
        std::vector<int32_t> touch_left, touch_right;
        for (int32_t i : ids) {
            const int32_t other = part_[i] == left ? right : left;
            for (int32_t p = pattern_.row_offsets[i]; p < pattern_.row_offsets[i + 1]; ++p) {
                if (part_[pattern_.columns[p]] == other) {
                    (part_[i] == left ? touch_left : touch_right).push_back(i);
                    break;
                }
            }
        }
        std::vector<int32_t>& separator =
            touch_left.size() <= touch_right.size() ? touch_left : touch_right;
        const int32_t separator_label = ++next_label_;
        for (int32_t i : separator) part_[i] = separator_label;

        std::vector<int32_t> left_ids, right_ids;
        left_ids.reserve(half);
        right_ids.reserve(ids.size() - half);
        for (int32_t i : ids) {
            if (part_[i] == left) left_ids.push_back(i);
            if (part_[i] == right) right_ids.push_back(i);
        }
        std::vector<int32_t>().swap(ids);  // release before recursing: depth is log2(n)
        dissect(left_ids);
        dissect(right_ids);
        order_.insert(order_.end(), separator.begin(), separator.end());
    }

    const SparsePattern& pattern_;
    const std::vector<Eigen::Vector3d>& coordinates_;
    std::vector<int32_t> part_;
    std::vector<int32_t> order_;
    int32_t next_label_ = 0;
};

}  // namespace

std::vector<int32_t> nested_dissection_order(const SparsePattern& pattern,
                                             const std::vector<Eigen::Vector3d>& coordinates) {
    return Dissection(pattern, coordinates).run();
}

}  // namespace raps
