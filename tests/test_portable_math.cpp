// The portable elementary functions (src/core/portable_math.h) against the C library's long
// double ones (x87 extended precision on x86-64: 11 more bits than double, so its own error is
// negligible here), on fixed pseudo-random arguments. The one test of an internal part: it links
// the library's objects, since the C ABI offers no way to call these alone. Prints the largest
// error of each function in units in the last place (docs/reproducibility.md quotes them).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>

extern "C" {
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>
}

#include "core/portable_math.h"
#include "support/split_mix.h"

namespace {

constexpr int kSamples = 200000;

// |got - exact| in units of the last place of the double nearest `exact`.
double ulp_error(double got, long double exact) {
    if (std::isnan(got) || std::isnan(exact)) return std::isnan(got) == std::isnan(exact) ? 0 : 1e9;
    const double rounded = static_cast<double>(exact);
    if (std::isinf(rounded)) return got == rounded ? 0.0 : 1e9;
    const int e = rounded == 0.0 ? -1074 : std::max(std::ilogb(rounded) - 52, -1074);
    return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) /
                               std::ldexp(1.0L, e));
}

template <typename Portable, typename Reference, typename Argument>
double worst_error(const char* name, Portable portable, Reference reference, Argument argument,
                   double bound) {
    Random random{0x5eed};
    double worst = 0.0, worst_at = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const double x = argument(random);
        const double error = ulp_error(portable(x), reference(static_cast<long double>(x)));
        if (error > worst) worst = error, worst_at = x;
    }
    std::printf("%-28s max error %.3f ulp (at %.17g), bound %.1f\n", name, worst, worst_at, bound);
    return worst;
}

#define ASSERT_ERROR_BELOW(bound, name, portable, reference, argument) \
    assert_true(worst_error(name, portable, reference, argument, bound) < (bound))

void exp_is_within_one_ulp(void** state) {
    (void)state;
    ASSERT_ERROR_BELOW(
        1.0, "exp on [-745, 709.78]", raps::portable::exp, [](long double x) { return expl(x); },
        [](Random& r) { return r.uniform(-745.0, 709.78); });
    ASSERT_ERROR_BELOW(
        1.0, "exp on [-2, 2]", raps::portable::exp, [](long double x) { return expl(x); },
        [](Random& r) { return r.uniform(-2.0, 2.0); });
}

void log_is_within_one_ulp(void** state) {
    (void)state;
    ASSERT_ERROR_BELOW(
        1.0, "log on (0, 2^1024)", raps::portable::log, [](long double x) { return logl(x); },
        [](Random& r) { return r.log_uniform(-1074, 1023); });
    ASSERT_ERROR_BELOW(
        1.0, "log on [0.9, 1.1]", raps::portable::log, [](long double x) { return logl(x); },
        [](Random& r) { return r.uniform(0.9, 1.1); });
    ASSERT_ERROR_BELOW(
        2.0, "log2 on (0, 2^1024)", raps::portable::log2, [](long double x) { return log2l(x); },
        [](Random& r) { return r.log_uniform(-1074, 1023); });
}

void sin_cos_are_within_one_ulp(void** state) {
    (void)state;
    for (double range : {8.0 * M_PI, 1e5}) {
        char name[2][64];
        std::snprintf(name[0], sizeof name[0], "sin on [-%g, %g]", range, range);
        std::snprintf(name[1], sizeof name[1], "cos on [-%g, %g]", range, range);
        auto argument = [range](Random& r) { return r.uniform(-range, range); };
        ASSERT_ERROR_BELOW(
            1.0, name[0], raps::portable::sin, [](long double x) { return sinl(x); }, argument);
        ASSERT_ERROR_BELOW(
            1.0, name[1], raps::portable::cos, [](long double x) { return cosl(x); }, argument);
    }
}

void tan_is_within_two_and_a_half_ulp(void** state) {
    (void)state;
    ASSERT_ERROR_BELOW(
        2.5, "tan on [-pi/2, pi/2]", raps::portable::tan, [](long double x) { return tanl(x); },
        [](Random& r) { return r.uniform(-M_PI / 2.0, M_PI / 2.0); });
    ASSERT_ERROR_BELOW(
        2.5, "tan on [-100, 100]", raps::portable::tan, [](long double x) { return tanl(x); },
        [](Random& r) { return r.uniform(-100.0, 100.0); });
}

// atan2 of both signs and magnitudes 2^-40..2^40 apart, as one argument: y over a fixed x set.
void atan2_is_within_one_and_a_half_ulp(void** state) {
    (void)state;
    Random xs{0xa7a2};
    double worst = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const double y = (xs.next() & 1 ? -1.0 : 1.0) * xs.log_uniform(-20, 20);
        const double x = (xs.next() & 1 ? -1.0 : 1.0) * xs.log_uniform(-20, 20);
        worst = std::max(
            worst, ulp_error(raps::portable::atan2(y, x), atan2l(static_cast<long double>(y), x)));
    }
    std::printf("%-28s max error %.3f ulp, bound 1.5\n", "atan2, |y|,|x| in 2^[-20,21]", worst);
    assert_true(worst < 1.5);
}

void pow_is_within_two_ulp_where_raps_uses_it(void** state) {
    (void)state;
    Random random{0x90e};
    double worst = 0.0;
    for (int i = 0; i < kSamples; ++i) {
        const double x = random.uniform(0.1, 10.0);
        const double y = random.uniform(-1.0, 1.0) / std::fabs(std::log(x));
        worst = std::max(
            worst, ulp_error(raps::portable::pow(x, y), powl(static_cast<long double>(x), y)));
    }
    std::printf("%-28s max error %.3f ulp, bound 2.0\n", "pow, |y log x| <= 1", worst);
    assert_true(worst < 2.0);
}

void special_values_are_the_ieee_ones(void** state) {
    (void)state;
    namespace p = raps::portable;
    const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
    assert_true(p::exp(0.0) == 1.0 && p::exp(-inf) == 0.0 && p::exp(inf) == inf);
    assert_true(p::exp(710.0) == inf && p::exp(-746.0) == 0.0 && std::isnan(p::exp(nan)));
    assert_true(p::log(1.0) == 0.0 && p::log(0.0) == -inf && p::log(inf) == inf);
    assert_true(std::isnan(p::log(-1.0)) && std::isnan(p::log(nan)));
    assert_true(p::log2(8.0) == 3.0 && p::log2(0x1p-1074) == -1074.0);
    assert_true(p::sin(0.0) == 0.0 && std::signbit(p::sin(-0.0)) && p::cos(0.0) == 1.0);
    assert_true(std::isnan(p::sin(inf)) && std::isnan(p::cos(-inf)) && std::isnan(p::tan(nan)));
    assert_true(p::atan2(0.0, -1.0) == M_PI && p::atan2(-0.0, -1.0) == -M_PI);
    assert_true(p::atan2(0.0, -0.0) == M_PI && p::atan2(0.0, 0.0) == 0.0);
    assert_true(p::atan2(1.0, 0.0) == M_PI / 2 && p::atan2(-1.0, 0.0) == -M_PI / 2);
    assert_true(p::atan2(1.0, 1.0) == M_PI / 4 && p::atan2(inf, -inf) == 3 * M_PI / 4);
    assert_true(p::atan2(1.0, -inf) == M_PI && std::isnan(p::atan2(nan, 1.0)));
    assert_true(p::pow(0.0, 2.0) == 0.0 && p::pow(5.0, 0.0) == 1.0 &&
                std::isnan(p::pow(-2.0, 2.0)));
}

}  // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(exp_is_within_one_ulp),
        cmocka_unit_test(log_is_within_one_ulp),
        cmocka_unit_test(sin_cos_are_within_one_ulp),
        cmocka_unit_test(tan_is_within_two_and_a_half_ulp),
        cmocka_unit_test(atan2_is_within_one_and_a_half_ulp),
        cmocka_unit_test(pow_is_within_two_ulp_where_raps_uses_it),
        cmocka_unit_test(special_values_are_the_ieee_ones),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
