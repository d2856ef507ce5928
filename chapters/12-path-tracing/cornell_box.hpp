// cornell_box.hpp — the chapter's scene: a Cornell box lit by one sphere light.
//
// A box two units wide, high and deep (x in [-1, 1], y in [0, 2], the back
// wall at z = -1), a red wall on the left, a green one on the right, white
// floor, ceiling and back, two white spheres, and a small sphere light under
// the ceiling. Its walls are chapter 04's planes; a black plane just behind
// the camera closes the box, so no path leaves the scene and the camera sees
// the box's open face as its picture frame. The colours are the usual Cornell
// box reflectances, in linear RGB. (The lecture's picture plan has the left
// sphere of glass, chapter 09; until that chapter is part of the course it is
// white and diffuse.)
#pragma once

#include "path_scene.hpp"

namespace rt::ch12 {

template <class T>
struct cornell_view {
    vec3<T> eye{T(0), T(1), T(3.3)};
    vec3<T> look_at{T(0), T(1), T(0)};
    vec3<T> up{T(0), T(1), T(0)};
    T vertical_fov_degrees = T(40);
};

template <class T>
path_scene<T> cornell_box() {
    path_scene<T> s;
    enum { white, red, green, light, black };
    s.surfaces = {
        {color(0.73f, 0.73f, 0.73f), color(0.0f)},
        {color(0.63f, 0.065f, 0.05f), color(0.0f)},
        {color(0.14f, 0.45f, 0.091f), color(0.0f)},
        {color(0.0f), color(17.0f, 15.0f, 12.0f)},  // a warm light, albedo 0: it only emits
        {color(0.0f), color(0.0f)},
    };
    auto& g = s.geometry;
    g.spheres = {
        {vec3<T>(T(0), T(1.75), T(-0.1)), T(0.18), light},
        {vec3<T>(T(-0.45), T(0.4), T(-0.35)), T(0.4), white},
        {vec3<T>(T(0.5), T(0.3), T(0.25)), T(0.3), white},
    };
    s.lights = {0};
    g.planes = {
        {vec3<T>(T(0), T(0), T(0)), vec3<T>(T(0), T(1), T(0)), white},     // floor
        {vec3<T>(T(0), T(2), T(0)), vec3<T>(T(0), T(-1), T(0)), white},    // ceiling
        {vec3<T>(T(0), T(0), T(-1)), vec3<T>(T(0), T(0), T(1)), white},    // back
        {vec3<T>(T(-1), T(0), T(0)), vec3<T>(T(1), T(0), T(0)), red},      // left
        {vec3<T>(T(1), T(0), T(0)), vec3<T>(T(-1), T(0), T(0)), green},    // right
        {vec3<T>(T(0), T(0), T(3.4)), vec3<T>(T(0), T(0), T(-1)), black},  // behind the camera
    };
    s.background = color(0.0f);
    return s;
}

}  // namespace rt::ch12
