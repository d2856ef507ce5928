// pixel_random.hpp — the random numbers of one pixel, the same on every run.
//
// Each pixel has its own stream, seeded by the picture's seed and the
// pixel's number, so a picture does not depend on how many threads draw it
// or in which order its rows are handed out. The generator is SplitMix64
// (Steele, Lea and Flood, "Fast splittable pseudorandom number generators",
// OOPSLA 2014): 64 bits of state, every output a strong mix of it, and
// defined by its integer operations alone, so every machine draws the same
// numbers (std::uniform_real_distribution is not specified that precisely).
#pragma once

#include "path_tracing.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace rt::ch12 {

class pixel_random {
public:
    pixel_random(std::uint64_t seed, std::uint64_t pixel) : state_(mix(seed ^ mix(pixel + 0x632be59bd9b4e019ULL))) {}

    // A number in [0, 1): the top bits of the next output, exactly
    // representable in T (24 bits for float, 53 for double), so it never rounds up to 1.
    template <class T>
    T uniform() {
        constexpr int bits = std::numeric_limits<T>::digits;
        return T(next() >> (64 - bits)) * (T(1) / T(std::uint64_t(1) << bits));
    }

    // The numbers one path needs: a vertex's five per bounce, for `vertices` vertices.
    template <class T>
    std::vector<bounce_numbers<T>> path_numbers(int vertices) {
        std::vector<bounce_numbers<T>> out(static_cast<size_t>(vertices));
        for (bounce_numbers<T>& b : out) {
            b.light_u1 = uniform<T>();
            b.light_u2 = uniform<T>();
            b.bounce_u1 = uniform<T>();
            b.bounce_u2 = uniform<T>();
            b.roulette_u = uniform<T>();
        }
        return out;
    }

private:
    static std::uint64_t mix(std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    std::uint64_t next() { return mix(state_ += 0x9e3779b97f4a7c15ULL); }

    std::uint64_t state_;
};

}  // namespace rt::ch12
