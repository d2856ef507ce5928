// robust_sphere.cpp — YOUR CODE for chapter 07. See robust_sphere.hpp for the
// contracts and README.md for the lecture. Write the steps in the README's
// order; each has its own public tests (ctest --preset student -L ch07 -R step1, ...).
#include "robust_sphere.hpp"

#include "common/stub.hpp"

namespace rt::ch07 {

// Step 1: a = d.d, half_b = f.d and a r^2 - |f x d|^2, as pairs (error_free.hpp).
template <class T>
quadratic<T> quarter_discriminant(const scaled_problem<T>& p) {
    (void)p;
    RT_NOT_IMPLEMENTED("chapter 07", "quarter_discriminant");
}

// Step 2: q = -(half_b + copysign(sqrt(quarter_disc), half_b)); roots c / q and q / a, ordered.
template <class T>
root_pair<T> stable_roots(wide<T> a, wide<T> half_b, wide<T> c, wide<T> quarter_disc) {
    (void)a, (void)half_b, (void)c, (void)quarter_disc;
    RT_NOT_IMPLEMENTED("chapter 07", "stable_roots");
}

// Step 3: c = f.f - radius^2 from the exact pieces of the squares, summed with sum_k3.
template <class T>
wide<T> constant_term(const scaled_problem<T>& p) {
    (void)p;
    RT_NOT_IMPLEMENTED("chapter 07", "constant_term");
}

// Step 4: f = o - C exactly (two_sum), then f and the radius scaled by 2^ef, d by 2^ed.
template <class T>
scaled_problem<T> scaled_offset(const sphere<T>& s, const ray<T>& r) {
    (void)s, (void)r;
    RT_NOT_IMPLEMENTED("chapter 07", "scaled_offset");
}

// Step 5: t = t' 2^exponent, rounded to T once.
template <class T>
T unscaled_root(wide<T> t_scaled, int exponent) {
    (void)t_scaled, (void)exponent;
    RT_NOT_IMPLEMENTED("chapter 07", "unscaled_root");
}

// Step 6: check the inputs, then steps 4, 1, 3, 2 and 5; pick the root in range; point and normal.
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    (void)s, (void)r, (void)range;
    RT_NOT_IMPLEMENTED("chapter 07", "intersect_sphere_robust");
}

// Compile the exercise for every precision the course uses (--error uses
// your long double version at some sizes). Leave these lines as they are.
#define RT_CH07_INSTANTIATE(T)                                                                                   \
    template quadratic<T> quarter_discriminant(const scaled_problem<T>&);                                       \
    template root_pair<T> stable_roots<T>(wide<T>, wide<T>, wide<T>, wide<T>);                                  \
    template wide<T> constant_term(const scaled_problem<T>&);                                                   \
    template scaled_problem<T> scaled_offset(const sphere<T>&, const ray<T>&);                                  \
    template T unscaled_root<T>(wide<T>, int);                                                                  \
    template std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>&, const ray<T>&, const interval<T>&);
RT_CH07_INSTANTIATE(float)
RT_CH07_INSTANTIATE(double)
RT_CH07_INSTANTIATE(long double)

}  // namespace rt::ch07
