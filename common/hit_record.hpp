// hit_record.hpp — what an intersection routine reports about a hit.
#pragma once

#include "math.hpp"

namespace rt {

template <class T>
struct hit_record {
    T t = 0;          // ray parameter of the hit: the point is ray.at(t)
    vec3<T> point{};  // the hit point
    vec3<T> normal{}; // unit surface normal at the hit (its side is the routine's contract)
    int object = -1;  // index of the object hit in its scene, -1 when not from a scene
};

}  // namespace rt
