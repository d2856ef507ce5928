// math.hpp — the vector vocabulary of the course, a thin layer over GLM.
//
// Every numerical routine in the course is a template on its scalar type T,
// so the same source can be compiled and measured in float and in double in
// one program (chapter 07 does exactly that). The alias keeps the spelling
// short: vec3<T> is GLM's three-component vector of T.
//
// Conventions, written once for the whole course:
//   * right-handed coordinates; the camera looks down -z, +y is up;
//   * image row 0 is the top row of the picture;
//   * colours are linear RGB floats until the image is written to PNG.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <limits>

namespace rt {

template <class T>
using vec3 = glm::vec<3, T, glm::defaultp>;

// Scene descriptions are kept in double, as written in their files.
using vec3d = vec3<double>;

// Colours are always float: they are not part of any numerical experiment.
using color = glm::vec3;

using glm::cross;
using glm::dot;
using glm::length;
using glm::normalize;

template <class T>
inline constexpr T infinity = std::numeric_limits<T>::infinity();

// True when every component is a finite number (no NaN, no infinity).
template <class T>
bool is_finite(const vec3<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Converts a vector between precisions, e.g. vec3<double> to vec3<float>.
template <class To, class From>
vec3<To> convert(const vec3<From>& v) {
    return vec3<To>(static_cast<To>(v.x), static_cast<To>(v.y), static_cast<To>(v.z));
}

}  // namespace rt
