// interval.hpp — the range of ray parameters a hit may have.
//
// The course's one rule: a hit at parameter t counts when  tmin < t < tmax,
// strictly on both sides. Strict at tmin so a shadow ray does not re-hit the
// surface it leaves; strict at tmax so the scene loop, which shrinks tmax to
// the closest hit so far, does not accept a second hit at the same distance.
//
// The comparison is written so that NaN fails it: every comparison with a
// NaN is false, so surrounds(NaN) is false and a NaN can never pass as a hit.
// (That is one reason the project never builds with -ffast-math, which lets
// the compiler assume NaN does not occur and drop exactly this protection.)
#pragma once

#include "math.hpp"

namespace rt {

template <class T>
struct interval {
    T min = -infinity<T>;
    T max = infinity<T>;

    // t lies strictly inside: min < t < max. Named as in Ray Tracing in One
    // Weekend, where surrounds is the open test and contains the closed one;
    // no hit test here uses a closed range, so there is no contains.
    bool surrounds(T t) const { return min < t && t < max; }

    // The range for a camera's primary rays: in front of the image plane.
    static constexpr interval in_front_of_image_plane() { return {T(1), infinity<T>}; }
};

}  // namespace rt
