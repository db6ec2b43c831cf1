// Elementary functions from IEEE basic operations only, after Sun Microsystems' fdlibm 5.3
// (K.C. Ng et al., 1993; the kernels as revised in FreeBSD's msun): e_exp.c, e_log.c, k_sin.c,
// k_cos.c, e_rem_pio2.c (its medium case), s_atan.c and e_atan2.c. The polynomial coefficients
// are fdlibm's minimax fits; the code is written anew around them.
//
// Everything here must round identically on every platform: no libm call (std::abs, std::fmod
// and comparisons are exact), no fused multiply-add (the library is built with
// -ffp-contract=off), and the exponent arithmetic done on the bits.
#include "core/portable_math.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace raps::portable {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

uint64_t bits_of(double x) {
    uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

double from_bits(uint64_t b) {
    double x;
    std::memcpy(&x, &b, sizeof x);
    return x;
}

// The biased exponent field: 0 for zero and subnormals, 2047 for infinities and NaN.
int biased_exponent(double x) {
    return static_cast<int>((bits_of(x) >> 52) & 0x7ff);
}

// x * 2^k for x in [0.5, 2) and a result that is normal or, with k < -1021, subnormal (one
// rounding, in the last multiplication).
double scale_by_power_of_two(double x, int k) {
    if (k >= -1021) return from_bits(bits_of(x) + (static_cast<uint64_t>(k) << 52));
    return from_bits(bits_of(x) + (static_cast<uint64_t>(k + 1000) << 52)) * 0x1p-1000;
}

// ln 2 in two parts: kLn2Hi has 32 significant bits, so k * kLn2Hi is exact for |k| < 2^21.
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;

// Round to the nearest integer (ties to even) in IEEE arithmetic: exact for |t| < 2^51.
double round_to_integer(double t) {
    if (!(std::abs(t) < 0x1p51)) return t;
    return (t + 0x1.8p52) - 0x1.8p52;
}

// sin and cos of x + y on [-pi/4, pi/4], y the tail of a reduced argument (|y| < ulp(x) / 2).
double kernel_sin(double x, double y) {
    constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                     S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                     S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
    const double z = x * x, w = z * z;
    const double r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    const double v = z * x;
    return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

double kernel_cos(double x, double y) {
    constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                     C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                     C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
    const double z = x * x;
    double w = z * z;
    const double r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
    const double hz = 0.5 * z;
    w = 1.0 - hz;
    return w + (((1.0 - w) - hz) + (z * r - x * y));
}

// x = n pi/2 + (y0 + y1) with |y0 + y1| <= about pi/4; returns n mod 4. pi/2 is taken in up to
// three parts of 33 bits each, the later ones only when the first leaves too few bits (fdlibm's
// medium case, exact products for |n| < 2^20).
int reduce_by_half_pi(double x, double& y0, double& y1) {
    constexpr double kTwoOverPi = 6.36619772367581382433e-01;
    constexpr double P1 = 1.57079632673412561417e+00, P1t = 6.07710050650619224932e-11;
    constexpr double P2 = 6.07710050630396597660e-11, P2t = 2.02226624879595063154e-21;
    constexpr double P3 = 2.02226624871116645580e-21, P3t = 8.47842766036889956997e-32;
    const double n = round_to_integer(x * kTwoOverPi);
    double r = x - n * P1;
    double w = n * P1t;
    y0 = r - w;
    const int e = biased_exponent(x);
    if (e - biased_exponent(y0) > 16) {
        double t = r;
        w = n * P2;
        r = t - w;
        w = n * P2t - ((t - r) - w);
        y0 = r - w;
        if (e - biased_exponent(y0) > 49) {
            t = r;
            w = n * P3;
            r = t - w;
            w = n * P3t - ((t - r) - w);
            y0 = r - w;
        }
    }
    y1 = (r - y0) - w;
    const double quadrant = std::abs(n) < 0x1p62 ? n : std::fmod(n, 4.0);
    return static_cast<int>(static_cast<int64_t>(quadrant) & 3);
}

constexpr double kQuarterPi = 7.85398163397448278999e-01;

// atan on [0, inf), fdlibm's s_atan.c: atan(x) = atan(c) + atan((x - c) / (1 + x c)) for the
// breakpoint c in {0, 1/2, 1, 3/2, inf} nearest x, then an odd polynomial.
double atan_nonnegative(double x) {
    constexpr double kAtanHi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01,
                                  9.82793723247329054082e-01, 1.57079632679489655800e+00};
    constexpr double kAtanLo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17,
                                  1.39033110312309984516e-17, 6.12323399573676603587e-17};
    constexpr double T[] = {
        3.33333333333329318027e-01,  -1.99999999998764832476e-01, 1.42857142725034663711e-01,
        -1.11111104054623557880e-01, 9.09088713343650656196e-02,  -7.69187620504482999495e-02,
        6.66107313738753120669e-02,  -5.83357013379057348645e-02, 4.97687799461593236017e-02,
        -3.65315727442169155270e-02, 1.62858201153657823623e-02};
    if (x >= 0x1p66) return kAtanHi[3] + kAtanLo[3];
    int id = -1;
    if (x < 0.4375) {
        if (x < 0x1p-27) return x;
    } else if (x < 1.1875) {
        if (x < 0.6875) {
            id = 0;
            x = (2.0 * x - 1.0) / (2.0 + x);
        } else {
            id = 1;
            x = (x - 1.0) / (x + 1.0);
        }
    } else if (x < 2.4375) {
        id = 2;
        x = (x - 1.5) / (1.0 + 1.5 * x);
    } else {
        id = 3;
        x = -1.0 / x;
    }
    const double z = x * x, w = z * z;
    const double s1 = z * (T[0] + w * (T[2] + w * (T[4] + w * (T[6] + w * (T[8] + w * T[10])))));
    const double s2 = w * (T[1] + w * (T[3] + w * (T[5] + w * (T[7] + w * T[9]))));
    if (id < 0) return x - x * (s1 + s2);
    return kAtanHi[id] - ((x * (s1 + s2) - kAtanLo[id]) - x);
}

}  // namespace

double exp(double x) {
    constexpr double kOverflow = 7.09782712893383973096e+02;
    constexpr double kUnderflow = -7.45133219101941108420e+02;
    constexpr double kInvLn2 = 1.44269504088896338700e+00;
    constexpr double P1 = 1.66666666666666019037e-01, P2 = -2.77777777770155933842e-03,
                     P3 = 6.61375632143793436117e-05, P4 = -1.65339022054652515390e-06,
                     P5 = 4.13813679705723846039e-08;
    if (x != x) return x + x;
    if (x > kOverflow) return kInfinity;
    if (x < kUnderflow) return 0.0;
    if (std::abs(x) < 0x1p-28) return 1.0 + x;
    // x = k ln2 + r, |r| <= ln2 / 2, r = hi - lo in extra precision.
    const int k =
        std::abs(x) <= 0.5 * kLn2Hi ? 0 : static_cast<int>(x * kInvLn2 + (x < 0.0 ? -0.5 : 0.5));
    const double hi = x - k * kLn2Hi, lo = k * kLn2Lo;
    const double r = hi - lo;
    // exp(r) = 1 + r + r c / (2 - c) with c from a minimax fit of r (exp(r)+1)/(exp(r)-1).
    const double t = r * r;
    const double c = r - t * (P1 + t * (P2 + t * (P3 + t * (P4 + t * P5))));
    const double y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
    return k == 0 ? y : scale_by_power_of_two(y, k);
}

double log(double x) {
    constexpr double L1 = 6.666666666666735130e-01, L2 = 3.999999999940941908e-01,
                     L3 = 2.857142874366239149e-01, L4 = 2.222219843214978396e-01,
                     L5 = 1.818357216161805012e-01, L6 = 1.531383769920937332e-01,
                     L7 = 1.479819860511658591e-01;
    if (x != x) return x + x;
    if (x < 0.0) return kNaN;
    if (x == 0.0) return -kInfinity;
    if (x == kInfinity) return x;
    int k = 0;
    if (biased_exponent(x) == 0) {  // subnormal
        x *= 0x1p54;
        k = -54;
    }
    // x = 2^k (1 + f) with 1 + f in [sqrt(2)/2, sqrt(2)).
    const uint64_t b = bits_of(x);
    const uint32_t high = static_cast<uint32_t>(b >> 32) & 0x000fffff;
    const uint32_t i = (high + 0x95f64) & 0x100000;
    k += biased_exponent(x) - 1023 + static_cast<int>(i >> 20);
    const uint64_t mantissa = b & 0x000fffffffffffffull;
    const double f = from_bits(mantissa | (static_cast<uint64_t>(i ^ 0x3ff00000) << 32)) - 1.0;
    const double dk = k;
    if (((high + 2) & 0x000fffff) < 3) {  // |f| < 2^-20
        if (f == 0.0) return k == 0 ? 0.0 : dk * kLn2Hi + dk * kLn2Lo;
        const double R = f * f * (0.5 - 0.33333333333333333 * f);
        return k == 0 ? f - R : dk * kLn2Hi - ((R - dk * kLn2Lo) - f);
    }
    // log(1 + f) = 2s + s R(s^2), s = f / (2 + f), R a minimax fit.
    const double s = f / (2.0 + f);
    const double z = s * s, w = z * z;
    const double t1 = w * (L2 + w * (L4 + w * L6));
    const double t2 = z * (L1 + w * (L3 + w * (L5 + w * L7)));
    const double R = t2 + t1;
    const bool far_from_one =
        (static_cast<int32_t>(high - 0x6147a) | static_cast<int32_t>(0x6b851 - high)) > 0;
    if (far_from_one) {
        const double hfsq = 0.5 * f * f;
        if (k == 0) return f - (hfsq - s * (hfsq + R));
        return dk * kLn2Hi - ((hfsq - (s * (hfsq + R) + dk * kLn2Lo)) - f);
    }
    if (k == 0) return f - s * (f - R);
    return dk * kLn2Hi - ((s * (f - R) - dk * kLn2Lo) - f);
}

double log2(double x) {
    constexpr double kInvLn2 = 1.44269504088896338700e+00;
    if (!(x > 0.0) || x == kInfinity || biased_exponent(x) == 0) return log(x) * kInvLn2;
    // x = 2^e m with m in [sqrt(2)/2, sqrt(2)): powers of two give their exponent exactly, and
    // near 1 the sum does not cancel.
    int e = biased_exponent(x) - 1023;
    double m = from_bits((bits_of(x) & 0x000fffffffffffffull) | 0x3ff0000000000000ull);
    if (m > 1.41421356237309504880) {
        m *= 0.5;
        ++e;
    }
    return e + log(m) * kInvLn2;
}

double pow(double x, double y) {
    if (x == 1.0 || y == 0.0) return 1.0;
    if (x == 0.0 && y > 0.0) return 0.0;
    if (!(x > 0.0)) return kNaN;
    return exp(y * log(x));
}

double sin(double x) {
    if (std::abs(x) < kQuarterPi) return std::abs(x) < 0x1p-27 ? x : kernel_sin(x, 0.0);
    if (biased_exponent(x) == 0x7ff) return x - x;
    double y0, y1;
    switch (reduce_by_half_pi(x, y0, y1)) {
        case 0:
            return kernel_sin(y0, y1);
        case 1:
            return kernel_cos(y0, y1);
        case 2:
            return -kernel_sin(y0, y1);
        default:
            return -kernel_cos(y0, y1);
    }
}

double cos(double x) {
    if (std::abs(x) < kQuarterPi) return kernel_cos(x, 0.0);
    if (biased_exponent(x) == 0x7ff) return x - x;
    double y0, y1;
    switch (reduce_by_half_pi(x, y0, y1)) {
        case 0:
            return kernel_cos(y0, y1);
        case 1:
            return -kernel_sin(y0, y1);
        case 2:
            return -kernel_cos(y0, y1);
        default:
            return kernel_sin(y0, y1);
    }
}

double tan(double x) {
    if (std::abs(x) < kQuarterPi) {
        return std::abs(x) < 0x1p-27 ? x : kernel_sin(x, 0.0) / kernel_cos(x, 0.0);
    }
    if (biased_exponent(x) == 0x7ff) return x - x;
    double y0, y1;
    const int n = reduce_by_half_pi(x, y0, y1);
    const double s = kernel_sin(y0, y1), c = kernel_cos(y0, y1);
    return n % 2 == 0 ? s / c : -c / s;
}

double atan2(double y, double x) {
    constexpr double kPi = 3.1415926535897931160e+00, kPiLo = 1.2246467991473531772e-16;
    constexpr double kHalfPi = 1.5707963267948965580e+00;
    if (x != x || y != y) return x + y;
    if (x == 1.0) return y < 0.0 ? -atan_nonnegative(-y) : atan_nonnegative(y);
    const bool y_negative = std::signbit(y);
    bool x_negative = std::signbit(x);
    if (y == 0.0) return x_negative ? (y_negative ? -kPi : kPi) : y;
    if (x == 0.0) return y_negative ? -kHalfPi : kHalfPi;
    if (std::abs(x) == kInfinity) {
        double z;
        if (std::abs(y) == kInfinity)
            z = x_negative ? 3.0 * kQuarterPi : kQuarterPi;
        else
            z = x_negative ? kPi : 0.0;
        return y_negative ? -z : z;
    }
    if (std::abs(y) == kInfinity) return y_negative ? -kHalfPi : kHalfPi;
    // |y / x| beyond 2^60 or below 2^-60 (x < 0): the answer is pi/2 or pi to the last bit.
    const int k = biased_exponent(y) - biased_exponent(x);
    double z;
    if (k > 60) {
        z = kHalfPi + 0.5 * kPiLo;
        x_negative = false;
    } else if (x_negative && k < -60) {
        z = 0.0;
    } else {
        z = atan_nonnegative(std::abs(y / x));
    }
    if (!x_negative) return y_negative ? -z : z;
    return y_negative ? (z - kPiLo) - kPi : kPi - (z - kPiLo);
}

}  // namespace raps::portable
