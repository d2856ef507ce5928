// slab_test.cpp — reference solution for chapter 08: the robust slab test.
#include "08-acceleration/aabb.hpp"

#include <cmath>

namespace rt::ch08 {

template <class T>
std::optional<T> intersect_box(const aabb<T>& box, const ray<T>& r, const vec3<T>& inv_direction,
                               const interval<T>& range) {
    T entry = range.min;
    T exit = range.max;
    for (int k = 0; k < 3; ++k) {
        // The near plane is the one the ray meets first: lo when it travels
        // up the axis, hi when it travels down. signbit, not "< 0", so that a
        // direction of -0 (reciprocal -inf) also picks hi.
        const bool down = std::signbit(inv_direction[k]);
        const T near_plane = down ? box.hi[k] : box.lo[k];
        const T far_plane = down ? box.lo[k] : box.hi[k];
        // A subnormal direction component is not zero, but its reciprocal
        // overflows to infinity, which would treat the ray as parallel to a
        // slab it crosses: for that axis divide instead (two roundings, as
        // the product's three are within widen_exit's bound).
        const bool overflowed = std::isinf(inv_direction[k]) && r.direction[k] != T(0);
        const T t_near = overflowed ? (near_plane - r.origin[k]) / r.direction[k]
                                    : (near_plane - r.origin[k]) * inv_direction[k];
        const T t_far = overflowed ? (far_plane - r.origin[k]) / r.direction[k]
                                   : (far_plane - r.origin[k]) * inv_direction[k];
        // Written so that a NaN (0 * inf: the origin on a face plane of a slab
        // the ray is parallel to) fails the comparison and changes nothing;
        // such a ray lies in the closed slab for every t.
        entry = t_near > entry ? t_near : entry;
        exit = t_far < exit ? t_far : exit;
    }
    return entry <= widen_exit(exit) ? std::optional<T>(entry) : std::nullopt;
}

template std::optional<float> intersect_box(const aabb<float>&, const ray<float>&, const vec3<float>&,
                                            const interval<float>&);
template std::optional<double> intersect_box(const aabb<double>&, const ray<double>&, const vec3<double>&,
                                             const interval<double>&);

}  // namespace rt::ch08
