// scene_loop.cpp — reference solution for chapter 03.
#include "03-scene-loop/scene_loop.hpp"

namespace rt::ch03 {

template <class T>
std::optional<hit_record<T>> closest_hit(int object_count, const object_intersector<T>& intersect, const ray<T>& r,
                                         interval<T> range) {
    std::optional<hit_record<T>> closest;
    for (int i = 0; i < object_count; ++i) {
        // Only a hit nearer than the best so far can win, so each object is
        // asked about (tmin, closest t) instead of (tmin, tmax). Because the
        // interval is open at tmax, an equally distant hit later on does not
        // replace the first one.
        if (auto hit = intersect(i, r, range)) {
            hit->object = i;
            range.max = hit->t;
            closest = hit;
        }
    }
    return closest;
}

template std::optional<hit_record<float>> closest_hit(int, const object_intersector<float>&, const ray<float>&,
                                                      interval<float>);
template std::optional<hit_record<double>> closest_hit(int, const object_intersector<double>&, const ray<double>&,
                                                       interval<double>);

}  // namespace rt::ch03
