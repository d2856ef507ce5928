// sample_sequences.hpp — where the program's numbers in [0,1)^2 come from.
//
// Not an exercise: the exercises take their random numbers as arguments, and
// this is what hands them out. A pixel's samples use three 2-D points each
// (where in the pixel, where on the lens, where on the light); a
// pixel_sequence gives point `dimension` (0, 1, 2) of sample k, drawn in one
// of three ways (README, "Three ways to place n samples"):
//
//   random      every point independent and uniform (pcg32);
//   stratified  the n samples of a pixel fill a sqrt(n) x sqrt(n) grid of
//               strata, one jittered sample each (your stratified_sample);
//               each dimension visits the strata in its own shuffled order,
//               so the lens point of a sample is not tied to its pixel point;
//   halton      the Halton sequence (radical inverses in the bases 2 and 3,
//               5 and 7, 11 and 13), shifted by a random offset per pixel
//               and dimension (a Cranley-Patterson rotation) so that
//               neighbouring pixels do not repeat the same pattern.
//
// Every number comes from the pixel's own stream (common/random.hpp), so a
// pixel's samples are the same whichever thread draws them.
#pragma once

#include "sampling.hpp"

#include "common/random.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rt::ch11 {

enum class sequence_kind { random, stratified, halton };

inline const char* sequence_name(sequence_kind s) {
    return s == sequence_kind::random ? "random" : s == sequence_kind::stratified ? "stratified" : "halton";
}

// The radical inverse of i in base b (Halton 1960): the digits of i in base b
// mirrored about the point, i = d0 + d1 b + d2 b^2 + ... -> d0/b + d1/b^2 + ...
// Summed in double from the last digit, then rounded to T and kept below 1.
template <class T>
T radical_inverse(unsigned base, unsigned i) {
    double inverse = 0, scale = 1.0 / base;
    for (; i > 0; i /= base, scale /= base) inverse += double(i % base) * scale;
    const T x = T(inverse);
    return x < T(1) ? x : std::nextafter(T(1), T(0));
}

// x + shift wrapped into [0, 1).
template <class T>
T wrapped(T x, T shift) {
    const T y = x + shift;
    return y < T(1) ? y : y - T(1);
}

template <class T>
class pixel_sequence {
public:
    static constexpr int dimensions = 3;  // pixel, lens, light

    // The samples of one pixel, from its stream. Stratified needs a square
    // count of samples (1, 4, 9, 16, ...): throws std::invalid_argument otherwise.
    pixel_sequence(sequence_kind kind, int samples, pcg32 stream)
        : kind_(kind), samples_(samples), stream_(stream) {
        if (!(samples >= 1)) throw std::invalid_argument("at least one sample per pixel");
        if (kind == sequence_kind::stratified) {
            side_ = int(std::lround(std::sqrt(double(samples))));
            if (side_ * side_ != samples)
                throw std::invalid_argument("stratified sampling takes a square number of samples per pixel (1, 4, "
                                            "9, 16, ...), not " + std::to_string(samples));
            for (auto& order : order_) order = shuffled(samples);
        }
        if (kind == sequence_kind::halton)
            for (auto& shift : shift_) shift = {stream_.uniform<T>(), stream_.uniform<T>()};
    }

    // Point `dimension` of sample k (k = 0 .. samples - 1, in order).
    vec2<T> point(int dimension, int k) {
        switch (kind_) {
            case sequence_kind::random: return uniform();
            case sequence_kind::stratified:
                return stratified_sample(order_[size_t(dimension)][size_t(k)], side_, uniform());
            case sequence_kind::halton: {
                static constexpr unsigned bases[dimensions][2] = {{2, 3}, {5, 7}, {11, 13}};
                const vec2<T>& shift = shift_[size_t(dimension)];
                return {wrapped(radical_inverse<T>(bases[dimension][0], unsigned(k)), shift.x),
                        wrapped(radical_inverse<T>(bases[dimension][1], unsigned(k)), shift.y)};
            }
        }
        throw std::logic_error("pixel_sequence: unknown kind");
    }

private:
    vec2<T> uniform() { return {stream_.uniform<T>(), stream_.uniform<T>()}; }

    // 0 .. n-1 in a random order (Fisher-Yates, from the pixel's stream).
    std::vector<int> shuffled(int n) {
        std::vector<int> order(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) order[size_t(i)] = i;
        for (int i = n - 1; i > 0; --i) {
            const int j = int(stream_.next_bits() % std::uint32_t(i + 1));  // bias < n / 2^32: negligible here
            std::swap(order[size_t(i)], order[size_t(j)]);
        }
        return order;
    }

    sequence_kind kind_;
    int samples_;
    pcg32 stream_;
    int side_ = 0;
    std::array<std::vector<int>, dimensions> order_;
    std::array<vec2<T>, dimensions> shift_{};
};

}  // namespace rt::ch11
