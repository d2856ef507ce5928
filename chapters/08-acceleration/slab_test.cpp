// slab_test.cpp — YOUR CODE for chapter 08, exercise 1: the robust slab test.
// See aabb.hpp for the contract and README.md ("The slab test", "Zero
// directions", "A conservative slab test") for the lecture.
#include "aabb.hpp"

#include "common/stub.hpp"

namespace rt::ch08 {

template <class T>
std::optional<T> intersect_box(const aabb<T>& box, const ray<T>& r, const vec3<T>& inv_direction,
                               const interval<T>& range) {
    // Start from entry = range.min and exit = range.max. For each axis k:
    // the ray's parameters at the two planes lo[k] and hi[k] are
    // (plane - origin[k]) * inv_direction[k]; the smaller is this slab's
    // entry, the larger its exit. Keep the largest entry and the smallest exit,
    // writing each comparison so that a NaN (0 * infinity) changes nothing.
    // Finally widen the exit outwards (widen_exit) and compare: entry <= exit
    // is a hit at `entry`.
    (void)box;
    (void)r;
    (void)inv_direction;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 08", "intersect_box");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<float> intersect_box(const aabb<float>&, const ray<float>&, const vec3<float>&,
                                            const interval<float>&);
template std::optional<double> intersect_box(const aabb<double>&, const ray<double>&, const vec3<double>&,
                                             const interval<double>&);

}  // namespace rt::ch08
