// transform.cpp — YOUR CODE for chapter 10, exercises 1 to 3: a ray into an
// object's space, a normal back out of it, and the box of a placed object.
// See transform.hpp for the contracts and README.md ("Into the object's
// space", "Normals", "Boxes of placed objects") for the lecture.
#include "transform.hpp"

#include "common/stub.hpp"

namespace rt::ch10 {

template <class T>
ray<T> transform_ray(const affine3<T>& m, const ray<T>& r) {
    // The origin is a point: A o + b. The direction is a difference of two
    // points: A d, no translation, and do not normalise it (t must keep its
    // meaning).
    (void)m;
    (void)r;
    RT_NOT_IMPLEMENTED("chapter 10", "transform_ray");
}

template <class T>
vec3<T> transform_normal(const placement<T>& p, const vec3<T>& n) {
    // Not A n: the transpose of A's inverse (p.to_object.linear holds A^-1),
    // then normalise.
    (void)p;
    (void)n;
    RT_NOT_IMPLEMENTED("chapter 10", "transform_normal");
}

template <class T>
ch08::aabb<T> instance_box(const affine3<T>& to_world, const ch08::aabb<T>& box) {
    // All eight corners (lo or hi in each coordinate), each mapped to the
    // world; the box around them; then widen every face outwards by the pad
    // transform.hpp gives. An empty box stays empty.
    (void)to_world;
    (void)box;
    RT_NOT_IMPLEMENTED("chapter 10", "instance_box");
}

// Compile the exercises for both precisions. Leave these lines as they are.
template ray<float> transform_ray(const affine3<float>&, const ray<float>&);
template ray<double> transform_ray(const affine3<double>&, const ray<double>&);
template vec3<float> transform_normal(const placement<float>&, const vec3<float>&);
template vec3<double> transform_normal(const placement<double>&, const vec3<double>&);
template ch08::aabb<float> instance_box(const affine3<float>&, const ch08::aabb<float>&);
template ch08::aabb<double> instance_box(const affine3<double>&, const ch08::aabb<double>&);

}  // namespace rt::ch10
