// ray.hpp — a ray is the set of points  r(t) = origin + t * direction.
//
// The direction is *not* normalised in general: a pinhole camera's primary
// ray points from the eye to a pixel on the image plane at distance 1, so
// t = 1 is the image plane and t > 1 is in front of it (chapter 01). Code
// that needs a unit direction says so in its contract.
#pragma once

#include "math.hpp"

namespace rt {

template <class T>
struct ray {
    vec3<T> origin;
    vec3<T> direction;

    vec3<T> at(T t) const { return origin + t * direction; }
};

}  // namespace rt
