// sphere_pieces.hpp — the parts of the robust sphere test that the formulation
// study's compensated and mixed forms (sphere_formulations.hpp) share.
// The chapter 07 solution (../robust_sphere.cpp) holds the same sum in
// its own file, because a submission, and so the reference answer, is one file.
// Instructor side: these are exercise answers (chapter 07, step 3).
#pragma once

#include "07-precision/error_free.hpp"

#include <array>
#include <cstddef>

namespace rt::sphere_pieces {

// c = f.f - r^2 from its exact pieces: (hi + lo)^2 = hi^2 + 2 hi lo + lo^2 for
// each component of f, each product split into value and error (two_prod), and
// r^2 as a pair, all summed as if in three times W's precision (sum_k3). For a
// ray origin a fraction of an ULP off the surface c is 10^9 times smaller than
// f.f; a double-word sum would leave it tens of ULPs of error, this about one.
template <class W>
W exact_constant_term(const double_word<W> (&f)[3], double_word<W> radius_squared) {
    std::array<W, 17> terms{};
    std::size_t n = 0;
    for (const double_word<W>& x : f) {
        const double_word<W> square = two_prod(x.hi, x.hi), cross = two_prod(x.hi, W(2) * x.lo);
        terms[n++] = square.hi, terms[n++] = square.lo, terms[n++] = cross.hi, terms[n++] = cross.lo;
        terms[n++] = x.lo * x.lo;  // about 2^-100 of f.f in double: its own rounding cannot matter
    }
    terms[n++] = -radius_squared.hi, terms[n++] = -radius_squared.lo;
    return sum_k3(terms);
}

}  // namespace rt::sphere_pieces
