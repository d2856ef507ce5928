// instances.hpp — objects placed by transforms: the data a scene file's
// "objects" and "instances" become (scene_file.hpp, scenes/README.md).
//
// An instance is one object stored once and placed by an affine transform,
//     p  ->  linear * p + offset      (object space -> the space holding it),
// as often as a scene likes: a thousand copies of a mesh cost one mesh. An
// object may hold instances of other objects (instances of instances), so
// the level-10 sphereflake's 3.9 billion spheres are eleven objects of one
// sphere and nine instances each.
//
// This file is data: the transform and its inverse as the reader computed
// them, and the bookkeeping of how many shapes a scene holds once every
// instance is counted. Moving a ray into an object's space and a normal back
// out of it is chapter 10's exercise, not here.
#pragma once

#include "math.hpp"
#include "shapes.hpp"

#include <glm/mat3x3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rt {

using mat3d = glm::dmat3;  // GLM: column-major, m[column][row]

// An affine map p -> linear * p + offset.
struct affine_transform {
    mat3d linear{1.0};
    vec3d offset{0.0};
};

// first, then second: p -> second(first(p)).
inline affine_transform then(const affine_transform& first, const affine_transform& second) {
    return {second.linear * first.linear, second.linear * first.offset + second.offset};
}

// The inverse map (glm::inverse of the linear part). The caller checks
// first that the linear part is invertible (the scene reader refuses a
// singular one); for a singular one the result is not finite.
inline affine_transform inverted(const affine_transform& a) {
    const mat3d inverse = glm::inverse(a.linear);
    return {inverse, -(inverse * a.offset)};
}

// One placement of a defined object.
struct instance_placement {
    int object = 0;                  // index into scene_description::objects
    affine_transform to_parent;      // object space -> the space of what places it
    affine_transform from_parent;    // its inverse (the reader refuses a singular transform)
    std::string field;               // where it was written, e.g. "a.json: instances[3]", for messages
};

// An object that instances place: shapes in its own coordinates (materials
// are the scene's numbers) and instances of other objects.
struct object_definition {
    std::string name;  // for messages: "objects.tree", "instances[2]", "scenes/room.json"
    std::vector<sphere<double>> spheres;
    std::vector<plane<double>> planes;
    std::vector<triangle<double>> triangles;
    std::vector<instance_placement> instances;
};

// How many shapes a scene holds once every instance is expanded, counted
// without expanding anything; a count past 2^64 - 1 stays at that value.
struct expanded_counts {
    std::uint64_t spheres = 0, planes = 0, triangles = 0;
    std::uint64_t total() const;
};

// a + b and n * a, stopping at 2^64 - 1 instead of wrapping.
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b);
std::uint64_t saturating_multiply(std::uint64_t a, std::uint64_t n);

// The shapes of objects[o] with every instance in it expanded (the objects
// form no cycle: the reader refuses one).
std::vector<expanded_counts> expanded_counts_of(const std::vector<object_definition>& objects);

// The longest chain of instances inside objects[o]: 0 for an object without
// instances, 1 + its deepest child's otherwise.
std::vector<int> nesting_depths(const std::vector<object_definition>& objects);

}  // namespace rt
