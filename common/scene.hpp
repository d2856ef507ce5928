// scene.hpp — what a picture is made of: shapes, their materials, lights.
//
// A scene is plain data. Each shape has a material index; lights are points
// with an intensity, plus one ambient term. Chapters 03 to 06 build scenes
// like this in their programs and hand them to the students' code.
#pragma once

#include "math.hpp"
#include "shapes.hpp"

#include <vector>

namespace rt {

// How a surface responds to light: the parameters chapter 06 shades with.
struct material {
    color diffuse{0.8f, 0.8f, 0.8f};   // diffuse reflectance, per channel
    color specular{0.0f, 0.0f, 0.0f};  // highlight colour
    float shininess = 32.0f;           // highlight exponent: larger is a smaller, sharper highlight
    bool checker = false;              // planes: alternate diffuse and checker_color in unit squares
    color checker_color{0.2f, 0.2f, 0.2f};
};

struct point_light {
    vec3d position{0, 0, 0};
    color intensity{1, 1, 1};  // radiant intensity; falls off as 1 / distance^2
};

template <class T>
struct scene {
    std::vector<sphere<T>> spheres;
    std::vector<plane<T>> planes;
    std::vector<triangle<T>> triangles;
    std::vector<material> materials;  // each shape's `material` indexes this
    std::vector<point_light> lights;
    color ambient{0.05f, 0.05f, 0.05f};
    color background{0.5f, 0.7f, 1.0f};

    // Objects are numbered spheres first, then planes, then triangles: the
    // number a hit_record's `object` field carries.
    int object_count() const { return int(spheres.size() + planes.size() + triangles.size()); }
};

}  // namespace rt
