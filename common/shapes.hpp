// shapes.hpp — the data that describes each kind of surface.
//
// Only data lives here: how to intersect a ray with each shape is what the
// chapters teach, so those formulas live in the chapters (and solutions/),
// never in common/.
#pragma once

#include "math.hpp"

namespace rt {

// All points p with |p - center| = radius (chapter 02).
template <class T>
struct sphere {
    vec3<T> center{0, 0, 0};
    T radius = 1;
    int material = 0;  // index into scene::materials
};

// All points p with (p - point) . normal = 0 (chapter 04). The normal need
// not be unit length, but must not be zero.
template <class T>
struct plane {
    vec3<T> point{0, 0, 0};
    vec3<T> normal{0, 1, 0};
    int material = 0;
};

// The triangle with corners a, b, c (chapter 05). Seen from the side its
// normal (b - a) x (c - a) points to, the corners run counter-clockwise.
template <class T>
struct triangle {
    vec3<T> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    int material = 0;
};

}  // namespace rt
