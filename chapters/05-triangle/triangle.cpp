// triangle.cpp — YOUR CODE for chapter 05. See triangle.hpp for the contract
// and README.md for the lecture.
#include "triangle.hpp"

#include "common/stub.hpp"

namespace rt::ch05 {

template <class T>
vec3<T> barycentric(const triangle<T>& tri, const vec3<T>& p) {
    // With n = (b - a) x (c - a), each coordinate is the signed area of the
    // sub-triangle opposite its corner over the whole area, e.g.
    //     gamma = ((b - a) x (p - a)) . n / (n . n).
    // Zero area: return NaN in all three.
    (void)tri;
    (void)p;
    RT_NOT_IMPLEMENTED("chapter 05", "barycentric");
}

template <class T>
std::optional<hit_record<T>> intersect_triangle(const triangle<T>& tri, const ray<T>& r, const interval<T>& range) {
    // Step 1: hit the triangle's plane (chapter 04's formula).
    // Step 2: keep the hit only if it is inside all three edge half-planes.
    // Fill in t, point and the unit normal along (b - a) x (c - a).
    (void)tri;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 05", "intersect_triangle");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template vec3<float> barycentric(const triangle<float>&, const vec3<float>&);
template vec3<double> barycentric(const triangle<double>&, const vec3<double>&);
template std::optional<hit_record<float>> intersect_triangle(const triangle<float>&, const ray<float>&,
                                                             const interval<float>&);
template std::optional<hit_record<double>> intersect_triangle(const triangle<double>&, const ray<double>&,
                                                              const interval<double>&);

}  // namespace rt::ch05
