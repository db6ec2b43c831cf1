// Fixed pseudo-random draws for the C++ tests of internal parts: SplitMix64, so that every run
// draws the same numbers on every machine.
#pragma once

#include <cmath>
#include <cstdint>

struct Random {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1p-53;
    }
    // |x| with a uniformly random exponent in [lo, hi] and random mantissa bits.
    double log_uniform(int lo, int hi) {
        const int e = lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1));
        return std::ldexp(uniform(1.0, 2.0), e);
    }
};
