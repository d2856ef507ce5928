// robust_sphere.cpp — YOUR CODE for chapter 07. See robust_sphere.hpp for the
// contract and README.md for the lecture.
#include "robust_sphere.hpp"

#include "common/stub.hpp"

namespace rt::ch07 {

template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    // Same quadratic as chapter 02, three changes (README.md):
    //   1. discriminant from the foot of the perpendicular, subtracted before squaring;
    //   2. roots from the stable pair q = -(half_b + sign(half_b) sqrt(...)), c / q and q / a;
    //   3. c = f.f - radius^2 keeping the low halves of the squares (std::fma).
    // Then pick the nearer root inside range, and fill in t, point and normal.
    (void)s;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 07", "intersect_sphere_robust");
}

// Compile the exercise for every precision the course uses (long double is
// the chapter program's reference). Leave these lines as they are.
template std::optional<hit_record<float>> intersect_sphere_robust(const sphere<float>&, const ray<float>&,
                                                                  const interval<float>&);
template std::optional<hit_record<double>> intersect_sphere_robust(const sphere<double>&, const ray<double>&,
                                                                   const interval<double>&);
template std::optional<hit_record<long double>> intersect_sphere_robust(const sphere<long double>&,
                                                                        const ray<long double>&,
                                                                        const interval<long double>&);

}  // namespace rt::ch07
