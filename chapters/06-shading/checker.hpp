// checker.hpp — given code, not an exercise: the diffuse colour of a
// material at a point, for materials with a checker pattern.
//
// A checker material alternates between m.diffuse and m.checker_color in
// unit squares of the x-z plane, so it is meant for horizontal planes such as
// the ground. The squares are picked with floor() of x and z only: using y as
// well would make the colour flicker on a plane at y = 0, where the computed
// hit points land a rounding error above or below zero at random.
#pragma once

#include "common/math.hpp"
#include "common/scene.hpp"

#include <cmath>

namespace rt::ch06 {

// Returns m with m.diffuse replaced by the colour of the square `point` lies
// in (m unchanged when it has no checker pattern, or the point is not finite).
template <class T>
material material_at(const material& m, const vec3<T>& point) {
    if (!m.checker || !is_finite(point)) return m;
    // fmod rather than a cast to an integer: a huge coordinate stays defined.
    const double squares = std::floor(double(point.x)) + std::floor(double(point.z));
    material here = m;
    if (std::fmod(squares, 2.0) != 0.0) here.diffuse = m.checker_color;
    return here;
}

}  // namespace rt::ch06
