// scene_loop.cpp — YOUR CODE for chapter 03. See scene_loop.hpp for the
// contract and README.md for the lecture.
#include "scene_loop.hpp"

#include "common/stub.hpp"

namespace rt::ch03 {

template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range) {
    // Ask every object i = 0 .. object_count-1 with intersect(i, r, range),
    // keep the nearest hit (and remember which object it was), and let each
    // hit shrink the range so farther objects can no longer win.
    (void)object_count;
    (void)intersect;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 03", "closest_hit");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<hit_record<float>> closest_hit(int, const object_intersector<float>&, const ray<float>&,
                                                      interval<float>);
template std::optional<hit_record<double>> closest_hit(int, const object_intersector<double>&, const ray<double>&,
                                                       interval<double>);

}  // namespace rt::ch03
