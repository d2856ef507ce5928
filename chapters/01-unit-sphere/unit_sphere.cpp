// unit_sphere.cpp — YOUR CODE for chapter 01. See unit_sphere.hpp for the
// contract and README.md for the lecture.
#include "unit_sphere.hpp"

#include "common/stub.hpp"

namespace rt::ch01 {

template <class T>
std::optional<T> intersect_unit_sphere(const ray<T>& r, const interval<T>& range) {
    // Substitute r(t) into  p . p - 1 = 0  to get  A t^2 + B t + C = 0,
    // solve it, and return the nearer root that lies inside range.
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 01", "intersect_unit_sphere");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<float> intersect_unit_sphere(const ray<float>&, const interval<float>&);
template std::optional<double> intersect_unit_sphere(const ray<double>&, const interval<double>&);

}  // namespace rt::ch01
