// plane.cpp — YOUR CODE for chapter 04. See plane.hpp for the contract and
// README.md for the lecture.
#include "plane.hpp"

#include "common/stub.hpp"

namespace rt::ch04 {

template <class T>
std::optional<hit_record<T>> intersect_plane(const plane<T>& p, const ray<T>& r, const interval<T>& range) {
    // Substitute r(t) into  (x - p.point) . n = 0  and solve for t.
    // Before dividing by d . n, ask what it means when d . n is zero.
    // Fill in t, point and the plane's normal made unit length.
    (void)p;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 04", "intersect_plane");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<hit_record<float>> intersect_plane(const plane<float>&, const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> intersect_plane(const plane<double>&, const ray<double>&,
                                                           const interval<double>&);

}  // namespace rt::ch04
