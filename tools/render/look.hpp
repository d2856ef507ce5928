// look.hpp — how the renderer colours a hit when the scene has no lights.
//
// Without lights there is nothing for a shading model to compute, so the
// picture uses chapter 03's look: the surface colour, darker where the
// surface turns away from the viewer, so shapes read as shapes. Both the
// general and the specialised path use this one function, so their
// pictures agree.
#pragma once

#include "common/math.hpp"
#include "common/scene.hpp"

#include <algorithm>

namespace rt::render_tool {

template <class T>
color unlit_colour(const material& m, const vec3<T>& unit_normal, const vec3<T>& direction) {
    const T facing = std::max(T(0), -dot(unit_normal, direction) / length(direction));
    // facing is NaN only for a zero direction, which no camera produces;
    // written so a NaN still gives the darker colour, not a NaN pixel.
    const float f = facing > T(0) ? float(std::min(facing, T(1))) : 0.0f;
    return m.diffuse * (0.3f + 0.7f * f);
}

}  // namespace rt::render_tool
