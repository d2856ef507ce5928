// Chapter 11's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
#include "table_builds.hpp"
#include "11-sampling/sampling.hpp"

namespace rt::ch11 {
// Chapter 11's own types travel like the course's other structs (exact_bits.hpp).
template <class T, class F> void fields(pixel_sample<T>& x, F&& f) { f(x.offset, x.value); }
template <class T, class F> void fields(light_sample<T>& x, F&& f) {
    f(x.point, x.normal, x.direction, x.distance, x.pdf);
}
template <class T, class F> void fields(thin_lens<T>& x, F&& f) { f(x.aperture, x.focus_distance); }
#if defined(RT_RPC_JUDGE) || defined(RT_RPC_RUNNER)
// The filter travels as one byte; a byte that names no filter is a broken message. (A placeholder
// build, table_builds.hpp, sends nothing and has no rpc::writer.)
inline void put(rpc::writer& w, filter_kind f) { rpc::put(w, std::uint8_t(f == filter_kind::box ? 0 : 1)); }
inline void get(rpc::reader& r, filter_kind& f) {
    std::uint8_t byte = 0;
    rpc::get(r, byte);
    if (byte > 1) throw rpc::protocol_error("a filter that is neither box nor tent");
    f = byte == 0 ? filter_kind::box : filter_kind::tent;
}
#endif
}  // namespace rt::ch11

#if RT_RPC_DEFINES_STUBS
namespace rt::ch11 {
template <class T>
vec2<T> stratified_sample(int k, int n, const vec2<T>& u) {
    return RT_RPC_FORWARD(stratified_sample, k, n, u);
}
template <class T>
T filter_weight(filter_kind f, const vec2<T>& offset) {
    return RT_RPC_FORWARD(filter_weight, f, offset);
}
template <class T>
color pixel_estimate(filter_kind f, const std::vector<pixel_sample<T>>& samples) {
    return RT_RPC_FORWARD(pixel_estimate, f, samples);
}
template <class T>
std::optional<light_sample<T>> sample_sphere_light(const sphere<T>& light, const vec3<T>& from, const vec2<T>& u) {
    return RT_RPC_FORWARD(sample_sphere_light, light, from, u);
}
template <class T>
T sphere_light_pdf(const sphere<T>& light, const vec3<T>& from, const vec3<T>& direction) {
    return RT_RPC_FORWARD(sphere_light_pdf, light, from, direction);
}
template <class T>
ray<T> thin_lens_ray(const pinhole_camera<T>& camera, const thin_lens<T>& lens, T px, T py, const vec2<T>& lens_u) {
    return RT_RPC_FORWARD(thin_lens_ray, camera, lens, px, py, lens_u);
}
}  // namespace rt::ch11
#endif

RT_RPC_FUNCTION(rt::ch11, stratified_sample)
RT_RPC_FUNCTION(rt::ch11, filter_weight)
RT_RPC_FUNCTION(rt::ch11, pixel_estimate)
RT_RPC_FUNCTION(rt::ch11, sample_sphere_light)
RT_RPC_FUNCTION(rt::ch11, sphere_light_pdf)
RT_RPC_FUNCTION(rt::ch11, thin_lens_ray)
