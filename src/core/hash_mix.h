// Hashing and sizing for the open-addressing tables that find equal vertices and triangles.
#pragma once

#include <cstddef>
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

// Slots for an open-addressing table of up to `count` keys: a power of two (the index is
// hash & (size - 1)), at most half full so that linear probing stays short.
inline size_t hash_table_size(size_t count) {
    size_t size = 16;
    while (size < 2 * count) size *= 2;
    return size;
}

}  // namespace raps
