// Chapter 06's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// The occlusion test travels as a number: the judge keeps the shadow queries shade() may ask (the
// student's own shadow_ray for every light, on both sides of the surface, so a shade() that turns the
// normal round is caught by its colour rather than by an unexpected question) with the test's answer to
// each, and answers every question the runner sends (served.hpp, served_by_judge.hpp).
#include "served_by_judge.hpp"
#include "table_builds.hpp"
#include "06-shading/shading.hpp"

namespace rt::ch06 {
// shadow_ray's result travels like the course's other structs (exact_bits.hpp).
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
#if defined(RT_RPC_JUDGE)
// The occlusion table for one call of shade(): asks the runner for shadow_ray() of every light on
// both sides of the surface (a light or point shadow_ray refuses is left out: shade() cannot ask it).
template <class T>
rpc::judge_occlusion<T> occlusion_for(const occlusion_test<T>& occluded, const vec3<T>& point, const vec3<T>& normal,
                                       const std::vector<point_light>& lights) {
    const auto* served = occluded.template target<test::served_occlusion<T>>();
    if (served == nullptr)
        throw std::logic_error("a test gave shade() an occlusion test that is not rt::test::served_occlusion "
                               "(tests/support/rpc/served.hpp): the grader cannot answer it in the runner");
    std::vector<std::pair<ray<T>, interval<T>>> questions;
    for (const point_light& light : lights)
        for (const vec3<T>& n : {normal, -normal}) {
            try {
                const shadow_query<T> q = shadow_ray(point, n, convert<T>(light.position));
                questions.emplace_back(q.r, q.range);
            } catch (const rpc::runner_gone&) {
                throw;
            } catch (const std::exception&) {
            }
        }
    return {std::make_shared<test::occlusion_server<T>>(served->table_for(questions))};
}
#endif

template <class T>
color shade(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_viewer, const material& m,
            const std::vector<point_light>& lights, const color& ambient, const occlusion_test<T>& occluded) {
#if defined(RT_RPC_JUDGE)
    // A question shade() should not have asked is noted by the judge during the call; it is thrown
    // here, in the judge, where the student's code cannot catch it.
    const rpc::judge_occlusion<T> asked = occlusion_for(occluded, point, normal, lights);
    color answer;
    try {
        answer = RT_RPC_FORWARD_AS(color, shade, point, normal, to_viewer, m, lights, ambient, asked);
    } catch (const rpc::runner_gone&) {
        throw;
    } catch (...) {
        if (!asked.fault->empty()) throw std::logic_error(*asked.fault);
        throw;
    }
    if (!asked.fault->empty()) throw std::logic_error(*asked.fault);
    return answer;
#else
    return RT_RPC_FORWARD_AS(color, shade, point, normal, to_viewer, m, lights, ambient, occluded);
#endif
}
}  // namespace rt::ch06
#endif

RT_RPC_FUNCTION(rt::ch06, lambert)
RT_RPC_FUNCTION(rt::ch06, blinn_phong)
RT_RPC_FUNCTION(rt::ch06, shadow_ray_origin)
RT_RPC_FUNCTION(rt::ch06, shadow_ray)
RT_RPC_FUNCTION(rt::ch06, shade)
