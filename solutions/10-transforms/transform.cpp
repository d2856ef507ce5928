// transform.cpp — reference solution for chapter 10: rays, normals and boxes
// through an affine transform.
#include "10-transforms/transform.hpp"

#include <algorithm>
#include <cmath>

namespace rt::ch10 {

namespace {

// A x, each component a sum of three products, left to right.
template <class T>
vec3<T> times(const glm::mat<3, 3, T>& a, const vec3<T>& x) {
    return a[0] * x.x + a[1] * x.y + a[2] * x.z;
}

// |A| |x| + |b|: the sum of the magnitudes of the terms of A x + b, the
// scale every rounding in it is relative to.
template <class T>
vec3<T> magnitude(const affine3<T>& m, const vec3<T>& x) {
    const vec3<T> ax = glm::abs(x);
    return glm::abs(m.linear[0]) * ax.x + glm::abs(m.linear[1]) * ax.y + glm::abs(m.linear[2]) * ax.z +
           glm::abs(m.translation);
}

}  // namespace

template <class T>
ray<T> transform_ray(const affine3<T>& m, const ray<T>& r) {
    // The origin moves with the translation; the direction, a difference of
    // two points, does not. Not normalised: o' + t d' = m(o + t d) for every
    // t, so a hit's t is the same in both spaces.
    return {times(m.linear, r.origin) + m.translation, times(m.linear, r.direction)};
}

template <class T>
vec3<T> transform_normal(const placement<T>& p, const vec3<T>& n) {
    // (A^-1)^T n: row k of A^-1 (column k of its transpose) dotted with n.
    const glm::mat<3, 3, T>& inverse = p.to_object.linear;
    return normalize(vec3<T>(dot(inverse[0], n), dot(inverse[1], n), dot(inverse[2], n)));
}

template <class T>
ch08::aabb<T> instance_box(const affine3<T>& to_world, const ch08::aabb<T>& box) {
    ch08::aabb<T> out;
    if (box.empty()) return out;
    vec3<T> largest{0, 0, 0};  // M_k: the largest magnitude of a corner's terms
    for (int corner = 0; corner < 8; ++corner) {
        const vec3<T> c{corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                        corner & 4 ? box.hi.z : box.lo.z};
        out.grow(times(to_world.linear, c) + to_world.translation);
        largest = glm::max(largest, magnitude(to_world, c));
    }
    // Each corner, and each hit point later computed the same way, is within
    // gamma(4) M of exact: twice that, and once more for this widening's own
    // rounding.
    const vec3<T> pad = T(3) * gamma<T>(4) * largest;
    out.lo -= pad;
    out.hi += pad;
    return out;
}

template ray<float> transform_ray(const affine3<float>&, const ray<float>&);
template ray<double> transform_ray(const affine3<double>&, const ray<double>&);
template vec3<float> transform_normal(const placement<float>&, const vec3<float>&);
template vec3<double> transform_normal(const placement<double>&, const vec3<double>&);
template ch08::aabb<float> instance_box(const affine3<float>&, const ch08::aabb<float>&);
template ch08::aabb<double> instance_box(const affine3<double>&, const ch08::aabb<double>&);

}  // namespace rt::ch10
