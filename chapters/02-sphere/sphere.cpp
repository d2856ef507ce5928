// sphere.cpp — YOUR CODE for chapter 02. See sphere.hpp for the contract and
// README.md for the lecture.
#include "sphere.hpp"

#include "common/stub.hpp"

namespace rt::ch02 {

template <class T>
std::optional<hit_record<T>> intersect_sphere(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    // Substitute r(t) into  |p - C|^2 = R^2  to get  A t^2 + B t + C' = 0,
    // solve it, pick the nearer root that lies inside range, and fill in the
    // hit record: t, the point r.at(t) and the outward unit normal.
    (void)s;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 02", "intersect_sphere");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<hit_record<float>> intersect_sphere(const sphere<float>&, const ray<float>&,
                                                           const interval<float>&);
template std::optional<hit_record<double>> intersect_sphere(const sphere<double>&, const ray<double>&,
                                                            const interval<double>&);

}  // namespace rt::ch02
