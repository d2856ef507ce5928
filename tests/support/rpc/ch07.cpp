// Chapter 07's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "07-precision/robust_sphere.hpp"
#include "table_builds.hpp"

// How chapter 07's own types travel (exact_bits.hpp: a struct lists its members once). Found by
// argument-dependent lookup, so they live in the types' namespaces.
namespace rt {
template <class W, class F> void fields(double_word<W>& x, F&& f) { f(x.hi, x.lo); }
}  // namespace rt
namespace rt::ch07 {
template <class T, class F> void fields(scaled_problem<T>& x, F&& f) {
    f(x.f[0], x.f[1], x.f[2], x.d[0], x.d[1], x.d[2], x.radius, x.ef, x.ed);
}
template <class T, class F> void fields(quadratic<T>& x, F&& f) { f(x.a, x.half_b, x.quarter_disc); }
template <class T, class F> void fields(root_pair<T>& x, F&& f) { f(x.near, x.far); }
}  // namespace rt::ch07

#if RT_RPC_DEFINES_STUBS
namespace rt::ch07 {
template <class T>
quadratic<T> quarter_discriminant(const scaled_problem<T>& p) {
    return RT_RPC_FORWARD(quarter_discriminant, p);
}
template <class T>
root_pair<T> stable_roots(wide<T> a, wide<T> half_b, wide<T> c, wide<T> quarter_disc) {
    return RT_RPC_FORWARD(stable_roots, a, half_b, c, quarter_disc);
}
template <class T>
wide<T> constant_term(const scaled_problem<T>& p) {
    return RT_RPC_FORWARD(constant_term, p);
}
template <class T>
scaled_problem<T> scaled_offset(const sphere<T>& s, const ray<T>& r) {
    return RT_RPC_FORWARD(scaled_offset, s, r);
}
template <class T>
T unscaled_root(wide<T> t_scaled, int exponent) {
    return RT_RPC_FORWARD(unscaled_root, t_scaled, exponent);
}
template <class T>
std::optional<hit_record<T>> intersect_sphere_robust(const sphere<T>& s, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_sphere_robust, s, r, range);
}
}  // namespace rt::ch07
#endif

RT_RPC_FUNCTION(rt::ch07, quarter_discriminant)
RT_RPC_FUNCTION(rt::ch07, stable_roots)
RT_RPC_FUNCTION(rt::ch07, constant_term)
RT_RPC_FUNCTION(rt::ch07, scaled_offset)
RT_RPC_FUNCTION(rt::ch07, unscaled_root)
RT_RPC_FUNCTION(rt::ch07, intersect_sphere_robust)
