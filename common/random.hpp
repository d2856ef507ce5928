// random.hpp — the random numbers of the sampling chapters, the same on every run.
//
// The exercises of chapters 11 and 12 take their random numbers as arguments;
// the programs draw them here. Each pixel has a stream of its own, chosen by
// the picture's seed and the pixel's number, so a pixel's numbers do not
// depend on which thread renders it or in which order: a picture is the
// same, bit for bit, on every run and every thread count.
//
// The generator is PCG32 (O'Neill, "PCG: A family of simple fast
// space-efficient statistically good algorithms for random number
// generation", 2014; the minimal pcg32 of pcg-random.org): a 64-bit linear
// congruential state, and a 32-bit output that permutes the state's high
// bits (an xorshift, then a rotation the state's top bits choose). Its
// increment selects one of 2^63 streams, which is how pixels get theirs.
#pragma once

#include <cstdint>

namespace rt {

class pcg32 {
public:
    // The stream `stream` of the generator seeded with `seed`.
    pcg32(std::uint64_t seed, std::uint64_t stream) : increment_((stream << 1u) | 1u) {
        next_bits();
        state_ += seed;
        next_bits();
    }

    // 32 random bits.
    std::uint32_t next_bits() {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + increment_;
        const auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rotation = std::uint32_t(old >> 59u);
        return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
    }

    // A number in [0, 1), never 1: a whole number of T's spacing below 1,
    // so every value is exactly representable (24 bits for float, 53 for
    // double, from two draws).
    template <class T>
    T uniform();

private:
    std::uint64_t state_ = 0;
    std::uint64_t increment_;
};

template <>
inline float pcg32::uniform<float>() {
    return float(next_bits() >> 8u) * 0x1p-24f;
}

template <>
inline double pcg32::uniform<double>() {
    const std::uint64_t high = next_bits() >> 5u;  // 27 bits
    const std::uint64_t low = next_bits() >> 6u;   // 26 bits
    return double((high << 26u) | low) * 0x1p-53;
}

// The stream of pixel (col, row) of a picture `width` pixels wide.
inline pcg32 pixel_stream(std::uint64_t seed, int col, int row, int width) {
    return pcg32(seed, std::uint64_t(row) * std::uint64_t(width) + std::uint64_t(col));
}

}  // namespace rt
