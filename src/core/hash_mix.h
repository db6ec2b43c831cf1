// Hashing for the open-addressing tables that find equal vertices and triangles.
#pragma once

#include <cstdint>

namespace raps {

// SplitMix64's finaliser (Steele, Lea & Flood 2014): every input bit reaches every output bit,
// so keys that differ only in high bits (a double's sign and exponent) or only in low bits
// (small indices) still spread over the low bits a power-of-two table uses.
inline uint64_t mix_bits(uint64_t x) {
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

}  // namespace raps
