// robust_sphere.cpp — YOUR CODE for chapter 07. See robust_sphere.hpp for the
// contract and README.md for the lecture.
#include "robust_sphere.hpp"

#include "common/stub.hpp"

namespace rt::ch07 {

template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    // Same quadratic as chapter 02, arranged so no step loses digits (README.md, "The exercise"):
    //   0. f = o - C exactly (two-sum); scale f, radius and d by powers of two when they are
    //      tiny or huge (for float data you may compute everything in double instead);
    //   1. disc/4 = a r^2 - |f x d|^2, the perpendicular distance without subtracting squares,
    //      every product split exactly with std::fma and kept as a pair hi + lo;
    //   2. roots from the stable pair q = -(half_b + sign(half_b) sqrt(disc/4)), c / q and q / a;
    //   3. c = f.f - radius^2 from the exact pieces of the squares, added with a compensated sum.
    // Then pick the nearer root inside range, undo the scaling, and fill in t, point and normal.
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
