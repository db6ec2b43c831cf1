#include "sphere/exact_orientation.h"

#include <Eigen/Geometry>

namespace raps {
namespace {

// a = hi + lo with each half of a's significand (Veltkamp's split, exact below about 1e300).
void split(double a, double& hi, double& lo) {
    const double c = 134217729.0 * a;  // 2^27 + 1
    hi = c - (c - a);
    lo = a - hi;
}

// a * b = hi + lo exactly (Dekker's product). Not std::fma: that is a fused multiply-add
// instruction, which the library never uses (tests/check_libm_free.cmake), or a libm call
// where the processor has none; both give these same bits, slower or not at all.
void two_product(double a, double b, double& hi, double& lo) {
    hi = a * b;
    double a_hi, a_lo, b_hi, b_lo;
    split(a, a_hi, a_lo);
    split(b, b_hi, b_lo);
    lo = a_lo * b_lo - (((hi - a_hi * b_hi) - a_lo * b_hi) - a_hi * b_lo);
}

// a + b = hi + lo exactly (Knuth's two-sum).
void two_sum(double a, double b, double& hi, double& lo) {
    const double s = a + b, bv = s - a, av = s - bv;
    hi = s;
    lo = (a - av) + (b - bv);
}

// Adds x to the expansion e[0..n) (nonoverlapping, increasing magnitude); returns n + 1.
int grow_expansion(double* e, int n, double x) {
    double q = x;
    for (int i = 0; i < n; ++i) {
        double hi, lo;
        two_sum(q, e[i], hi, lo);
        e[i] = lo;
        q = hi;
    }
    e[n] = q;
    return n + 1;
}

// Every term a_i b_j c_k of the determinant as four doubles, summed exactly; the sign of an
// expansion is that of its largest nonzero component. Exact unless a product underflows
// (coordinates below about 1e-100).
int expansion_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    static constexpr int kPermutation[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                               {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
    double e[24];
    int n = 0;
    for (int p = 0; p < 6; ++p) {
        const double sign = p < 3 ? 1.0 : -1.0;
        const int i = kPermutation[p][0], j = kPermutation[p][1], k = kPermutation[p][2];
        double hi, lo, terms[4];
        two_product(sign * a[i], b[j], hi, lo);
        two_product(hi, c[k], terms[0], terms[1]);
        two_product(lo, c[k], terms[2], terms[3]);
        for (double term : terms) n = grow_expansion(e, n, term);
    }
    for (int m = n - 1; m >= 0; --m) {
        if (e[m] != 0.0) return e[m] > 0.0 ? 1 : -1;
    }
    return 0;
}

}  // namespace

int exact_orientation_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
    // a . ((b - a) x (c - a)) rounds by a few units of 2^-52 times |b - a| |c - a| (for unit
    // vectors); 1e-14 of that is a wide margin.
    const Eigen::Vector3d ab = b - a, ac = c - a;
    const double det = a.dot(ab.cross(ac));
    const double bound = 1e-14 * ab.norm() * ac.norm() * (1.0 + a.norm());
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return expansion_sign(a, b, c);
}

}  // namespace raps
