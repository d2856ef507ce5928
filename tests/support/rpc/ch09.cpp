// Chapter 09's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// Every argument is data (vectors, numbers, a surface point, a whole scene for trace), so each call
// travels as its exact bits; trace's recursion runs in the runner, calling the student's own optics
// and spawn there.
#include "table_builds.hpp"
#include "09-reflection/optics.hpp"
#include "09-reflection/spawn.hpp"
#include "09-reflection/whitted.hpp"

namespace rt::ch09 {
// A surface point travels like the course's other structs (exact_bits.hpp).
template <class T, class F>
void fields(surface_point<T>& x, F&& f) {
    f(x.point, x.error);
}
}  // namespace rt::ch09

#if RT_RPC_DEFINES_STUBS
namespace rt::ch09 {
template <class T>
vec3<T> reflect(const vec3<T>& d, const vec3<T>& n) {
    return RT_RPC_FORWARD(reflect, d, n);
}
template <class T>
std::optional<vec3<T>> refract(const vec3<T>& d, const vec3<T>& n, T eta) {
    return RT_RPC_FORWARD(refract, d, n, eta);
}
template <class T>
T fresnel_dielectric(T cos_i, T eta) {
    return RT_RPC_FORWARD(fresnel_dielectric, cos_i, eta);
}
template <class T>
T schlick(T cos_i, T eta) {
    return RT_RPC_FORWARD(schlick, cos_i, eta);
}
template <class T>
vec3<T> offset_ray_origin(const surface_point<T>& p, const vec3<T>& n, const vec3<T>& w) {
    return RT_RPC_FORWARD(offset_ray_origin, p, n, w);
}
template <class T>
color trace(const scene<T>& world, const ray<T>& r, const interval<T>& range, int depth, float throughput) {
    return RT_RPC_FORWARD(trace, world, r, range, depth, throughput);
}
}  // namespace rt::ch09
#endif

RT_RPC_FUNCTION(rt::ch09, reflect)
RT_RPC_FUNCTION(rt::ch09, refract)
RT_RPC_FUNCTION(rt::ch09, fresnel_dielectric)
RT_RPC_FUNCTION(rt::ch09, schlick)
RT_RPC_FUNCTION(rt::ch09, offset_ray_origin)
RT_RPC_FUNCTION(rt::ch09, trace)
