// Complex modulus and division with the same bits on every platform (core/portable_math.h says
// why): std::abs of a std::complex calls the C library's cabs (hypot, not correctly rounded),
// and a complex division calls the compiler runtime's __divdc3, which is built with fused
// multiply-adds on some architectures. Multiplication is left to the compiler: it is the plain
// formula in the library's own flags, with a runtime call only when that gives NaN (infinite or
// overflowing operands).
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace raps::portable {

// |z| without overflow or underflow in the squares; within 1.5 ulp.
inline double abs(const std::complex<double>& z) {
    const double x = std::abs(z.real()), y = std::abs(z.imag());
    const double big = std::max(x, y), small = std::min(x, y);
    if (big == std::numeric_limits<double>::infinity()) return big;
    if (x != x || y != y) return x + y;
    if (big == 0.0) return 0.0;
    const double r = small / big;
    return big * std::sqrt(1.0 + r * r);
}

// a / b by Smith's method (Smith, "Algorithm 116: Complex division", CACM 1962): no overflow in
// the intermediate squares. b = 0 gives infinities or NaN.
inline std::complex<double> divide(const std::complex<double>& a, const std::complex<double>& b) {
    if (std::abs(b.real()) >= std::abs(b.imag())) {
        const double r = b.imag() / b.real(), d = b.real() + b.imag() * r;
        return {(a.real() + a.imag() * r) / d, (a.imag() - a.real() * r) / d};
    }
    const double r = b.real() / b.imag(), d = b.real() * r + b.imag();
    return {(a.real() * r + a.imag()) / d, (a.imag() * r - a.real()) / d};
}

}  // namespace raps::portable
