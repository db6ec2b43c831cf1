/* Exact sign of a 3x3 determinant by floating-point expansions (Shewchuk, "Adaptive precision
 * floating-point arithmetic and fast robust geometric predicates", 1997): every product of
 * three doubles is written exactly as four doubles (two_product, by fma), and the 24 of them
 * are summed exactly into a nonoverlapping expansion (grow_expansion) whose largest component
 * has the sign of the sum. Exact unless a product underflows (coordinates below about 1e-100),
 * which spherical maps do not reach. */
#include "support/exact_orientation.h"

#include <math.h>

/* a * b = *hi + *lo exactly. */
static void two_product(double a, double b, double* hi, double* lo) {
    *hi = a * b;
    *lo = fma(a, b, -*hi);
}

/* a + b = *hi + *lo exactly (Knuth). */
static void two_sum(double a, double b, double* hi, double* lo) {
    const double s = a + b, bv = s - a, av = s - bv;
    *hi = s;
    *lo = (a - av) + (b - bv);
}

/* Adds x to the expansion e (n components, increasing magnitude, nonoverlapping). */
static int grow_expansion(double* e, int n, double x) {
    double q = x;
    for (int i = 0; i < n; ++i) {
        double hi, lo;
        two_sum(q, e[i], &hi, &lo);
        e[i] = lo;
        q = hi;
    }
    e[n] = q;
    return n + 1;
}

int exact_orientation_sign(const double* a, const double* b, const double* c) {
    /* det = sum over the permutations (i, j, k) of sign * a_i b_j c_k. */
    static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                   {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
    double e[24];
    int n = 0;
    for (int p = 0; p < 6; ++p) {
        const double sign = p < 3 ? 1.0 : -1.0;
        double hi, lo, terms[4];
        two_product(sign * a[perm[p][0]], b[perm[p][1]], &hi, &lo);
        two_product(hi, c[perm[p][2]], &terms[0], &terms[1]);
        two_product(lo, c[perm[p][2]], &terms[2], &terms[3]);
        for (int t = 0; t < 4; ++t) n = grow_expansion(e, n, terms[t]);
    }
    for (int i = n - 1; i >= 0; --i) {
        if (e[i] != 0.0) return e[i] > 0.0 ? 1 : -1;
    }
    return 0;
}
