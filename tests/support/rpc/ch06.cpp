// Chapter 06's exercise functions for the judge and the runner (table.hpp explains the two halves).
// The occlusion test is a callback: the student's shade() calls it in the runner, it runs in the judge.
#include "table.hpp"
#include "06-shading/shading.hpp"

namespace rt::ch06 {
// shadow_ray's result travels like the course's other structs (wire.hpp).
template <class T, class F>
void fields(shadow_query<T>& x, F&& f) {
    f(x.r, x.range);
}
}  // namespace rt::ch06

#if RT_RPC_DEFINES_STUBS
namespace rt::ch06 {
template <class T>
T lambert(const vec3<T>& normal, const vec3<T>& to_light) {
    return RT_RPC_FORWARD(lambert, normal, to_light);
}
template <class T>
T blinn_phong(const vec3<T>& normal, const vec3<T>& to_light, const vec3<T>& to_viewer, T shininess) {
    return RT_RPC_FORWARD(blinn_phong, normal, to_light, to_viewer, shininess);
}
template <class T>
vec3<T> shadow_ray_origin(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_light) {
    return RT_RPC_FORWARD(shadow_ray_origin, point, normal, to_light);
}
template <class T>
shadow_query<T> shadow_ray(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& light_position) {
    return RT_RPC_FORWARD(shadow_ray, point, normal, light_position);
}
template <class T>
color shade(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_viewer, const material& m,
            const std::vector<point_light>& lights, const color& ambient, const occlusion_test<T>& occluded) {
    return RT_RPC_FORWARD(shade, point, normal, to_viewer, m, lights, ambient, occluded);
}
}  // namespace rt::ch06
#endif

RT_RPC_FUNCTION(rt::ch06, lambert)
RT_RPC_FUNCTION(rt::ch06, blinn_phong)
RT_RPC_FUNCTION(rt::ch06, shadow_ray_origin)
RT_RPC_FUNCTION(rt::ch06, shadow_ray)
RT_RPC_FUNCTION(rt::ch06, shade)
