// Chapter 12's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// Every argument is plain data (the scene travels whole, the random numbers as a list), so no callback
// crosses: the runner's path_radiance intersects the scene with the earlier chapters' code on its side.
#include "table_builds.hpp"
#include "12-path-tracing/path_tracing.hpp"

// How chapter 12's own types travel (exact_bits.hpp: a struct lists its members once). Found by
// argument-dependent lookup, so they live in the types' namespace.
namespace rt::ch12 {
template <class F> void fields(surface& x, F&& f) { f(x.albedo, x.emission, x.ior); }
template <class T, class F> void fields(path_scene<T>& x, F&& f) {
    f(x.geometry.spheres, x.geometry.planes, x.surfaces, x.lights, x.background);
}
template <class T, class F> void fields(direction_sample<T>& x, F&& f) { f(x.direction, x.pdf); }
template <class T, class F> void fields(light_sample<T>& x, F&& f) { f(x.direction, x.pdf, x.radiance, x.object); }
template <class T, class F> void fields(bounce_numbers<T>& x, F&& f) {
    f(x.light_u1, x.light_u2, x.bounce_u1, x.bounce_u2, x.roulette_u);
}
template <class F> void fields(path_settings& x, F&& f) { f(x.next_event, x.cosine_sampling, x.roulette_after); }
}  // namespace rt::ch12

#if RT_RPC_DEFINES_STUBS
namespace rt::ch12 {
template <class T>
T cosine_hemisphere_pdf(const vec3<T>& normal, const vec3<T>& direction) {
    return RT_RPC_FORWARD(cosine_hemisphere_pdf, normal, direction);
}
template <class T>
direction_sample<T> cosine_hemisphere(const vec3<T>& normal, T u1, T u2) {
    return RT_RPC_FORWARD(cosine_hemisphere, normal, u1, u2);
}
template <class T>
color light_contribution(const color& albedo, const vec3<T>& normal, const light_sample<T>& l) {
    return RT_RPC_FORWARD(light_contribution, albedo, normal, l);
}
template <class T>
T roulette_weight(const color& throughput, T u) {
    return RT_RPC_FORWARD(roulette_weight, throughput, u);
}
template <class T>
color path_radiance(const path_scene<T>& s, const ray<T>& camera_ray, const interval<T>& camera_range,
                    const std::vector<bounce_numbers<T>>& numbers, const path_settings& settings) {
    return RT_RPC_FORWARD(path_radiance, s, camera_ray, camera_range, numbers, settings);
}
}  // namespace rt::ch12
#endif

RT_RPC_FUNCTION(rt::ch12, cosine_hemisphere_pdf)
RT_RPC_FUNCTION(rt::ch12, cosine_hemisphere)
RT_RPC_FUNCTION(rt::ch12, light_contribution)
RT_RPC_FUNCTION(rt::ch12, roulette_weight)
RT_RPC_FUNCTION(rt::ch12, path_radiance)
