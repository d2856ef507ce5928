// sphereflake.hpp — GIVEN: Eric Haines' sphereflake as instances of
// instances, and the same flake built flat.
//
// The sphereflake is self-similar: each of a sphere's nine children is the
// whole flake a third the size, turned to face away from its parent. So the
// flake of level L is one model holding ten instances: the root sphere
// (model 0, placed as it is) and nine placements of the flake of level L - 1.
// Level L needs L + 1 models of at most ten instances each, however many
// spheres it shows: 1 + 9 + ... + 9^L (level 10: 3,922,632,451).
//
// The directions are chapter 08's (common/spd.cpp's child_directions, as
// published by the SPD), taken in the root's own axes; chapter 08's flake
// (made of copies too, since common/spd.cpp gives every child the same turn
// relative to its parent) starts from another frame at the root, so the two
// flakes differ by how each ring of children is turned. flatten() gives the flat list of this one,
// numbered as the instances number them, for the tests that compare both.
//
// Data only: no intersection here.
#pragma once

#include "transform.hpp"

#include "common/math.hpp"
#include "common/shapes.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace rt::ch10 {

// One placement in a model, in double as a scene describes it.
struct part {
    affine3<double> to_world;
    int model = 0;
    std::int64_t first_object = 0;
};

// A model made of instances of the models before it.
struct composite_model {
    std::vector<part> parts;
    std::int64_t objects = 0;  // objects in the model, flattened
};

// The root sphere every model 0 is: radius 0.5 at the origin, on the ground z = -0.5.
template <class T>
sphere<T> flake_root_sphere(int material = 0) {
    return {vec3<T>(0), T(0.5), material};
}

inline std::int64_t flake_sphere_count(int level) {
    std::int64_t n = 1, power = 1;
    for (int k = 0; k < level; ++k) n += (power *= 9);
    return n;
}

// The nine placements of a flake's children relative to the flake itself
// (z up, root of radius 0.5 at the origin): each a third the size, turned so
// the child's own z points along its direction, touching the root.
inline std::vector<affine3<double>> flake_child_placements() {
    const double pi = std::acos(-1.0);
    std::vector<vec3d> dirs;
    for (int k = 0; k < 6; ++k) dirs.emplace_back(std::cos(k * pi / 3), std::sin(k * pi / 3), 0.0);
    const double elevation = std::asin(std::sqrt(2.0 / 3.0));
    for (int k = 0; k < 3; ++k) {
        const double azimuth = pi / 6 + k * 2 * pi / 3;
        dirs.emplace_back(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                          std::sin(elevation));
    }
    std::vector<affine3<double>> out;
    const double reach = 0.5 + 0.5 / 3;  // parent's radius plus the child's
    for (const vec3d& w : dirs) {
        const vec3d helper = std::fabs(w.x) > 0.9 ? vec3d(0, 1, 0) : vec3d(1, 0, 0);
        const vec3d u = normalize(cross(helper, w));
        const vec3d v = cross(w, u);
        out.push_back(compose(frame(u, v, w, reach * w), scale(vec3d(1.0 / 3))));
    }
    return out;
}

// Models 0 .. level of the flake of `level`: models[0] is empty (the root
// sphere, a shape: flake_root_sphere), models[k] for k >= 1 places model 0
// once as it is (object 0) and model k - 1 nine times (objects 1 .. ).
inline std::vector<composite_model> flake_models(int level) {
    if (level < 0 || level > 12) throw std::invalid_argument("the sphereflake's level must be 0 to 12");
    std::vector<composite_model> models(size_t(level) + 1);
    models[0].objects = 1;
    const std::vector<affine3<double>> children = flake_child_placements();
    for (int k = 1; k <= level; ++k) {
        composite_model& m = models[size_t(k)];
        m.parts.push_back({affine3<double>{}, 0, 0});
        std::int64_t next = 1;
        for (const affine3<double>& child : children) {
            m.parts.push_back({child, k - 1, next});
            next += models[size_t(k - 1)].objects;
        }
        m.objects = next;
    }
    return models;
}

// The flat flake: every sphere of model `which`, in its space, numbered as
// the instances number them (object j of the model is flat[j]). Positions
// are composed in double, then rounded once to T. Only for small levels (the
// tests compare it with the instanced one).
template <class T>
std::vector<sphere<T>> flatten(const std::vector<composite_model>& models, int which,
                               const affine3<double>& to_world = {}, double size = 1) {
    std::vector<sphere<T>> out;
    if (which == 0) {
        const sphere<double> root = flake_root_sphere<double>();
        out.push_back({convert<T>(to_world.linear * root.center + to_world.translation), T(root.radius * size), 0});
        return out;
    }
    for (const part& p : models[size_t(which)].parts) {
        // The parts' scales are uniform: the radius scales by the first column's length.
        const double s = size * glm::length(p.to_world.linear[0]);
        const std::vector<sphere<T>> inner = flatten<T>(models, p.model, compose(to_world, p.to_world), s);
        out.insert(out.end(), inner.begin(), inner.end());
    }
    return out;
}

}  // namespace rt::ch10
