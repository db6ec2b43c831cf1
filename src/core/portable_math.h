// Elementary functions that give the same bits on every platform, for the results' path.
//
// The C library's exp, log, sin, cos, tan, atan2 and pow are not correctly rounded, and their
// last bit differs between C libraries (glibc, musl, Apple's, Microsoft's), between
// architectures, and on x86-64 even between processors (glibc picks FMA-compiled variants at run
// time). These are built from IEEE basic operations only (+, -, *, / and comparisons, each
// correctly rounded on every platform) with the library's -ffp-contract=off, so they return the
// same bits wherever IEEE double arithmetic rounds to nearest (docs/reproducibility.md).
//
// The algorithms are those of Sun's fdlibm (K.C. Ng et al., 1993): reduction by an extra-precise
// constant, then a minimax polynomial or rational kernel. Largest error measured against long
// double (tests/test_portable_math.cpp, 200,000 arguments per range): exp 0.85 ulp, log 0.81,
// sin and cos 0.76, atan2 1.33 (y / x rounds first), log2 1.17, tan 2.02 (sine over cosine),
// pow 1.81 where |y log x| <= 1 (exp of y log x).
#pragma once

namespace raps::portable {

double exp(double x);
double log(double x);
double log2(double x);
// x^y for x > 0 as exp(y log x): its error grows with |y log x| (about 1 ulp more per 2^10 of
// it); raps uses it with |y log x| < 1. x <= 0 gives NaN but for pow(0, y > 0) = 0.
double pow(double x, double y);
// Arguments are reduced by pi/2 in three parts (fdlibm's medium reduction): accurate for
// |x| < 2^20 pi/2, deterministic (and less accurate) beyond, NaN for infinities.
double sin(double x);
double cos(double x);
double tan(double x);
double atan2(double y, double x);

}  // namespace raps::portable
