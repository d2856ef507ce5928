// Chapter 10's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// Transforms, placements, instances and the top-level tree travel whole (they are small); the model
// callback travels as a number: the judge answers each model the student's code asks about
// (served_by_judge.hpp), and its record of those calls decides the test's rules (served.hpp): the model
// must be an instance's, the ray that instance's transform_ray(to_object, r), the range as the test says.
#include "10-transforms/instancing.hpp"
#include "10-transforms/transform.hpp"
#include "ch08_fields.hpp"
#include "served_by_judge.hpp"
#include "table_builds.hpp"

namespace rt::ch10 {
template <class T, class F>
void fields(affine3<T>& x, F&& f) {
    f(x.linear[0], x.linear[1], x.linear[2], x.translation);
}
template <class T, class F>
void fields(placement<T>& x, F&& f) {
    f(x.to_world, x.to_object);
}
template <class T, class F>
void fields(instance<T>& x, F&& f) {
    f(x.place, x.model, x.first_object);
}
template <class T, class F>
void fields(instance_tree<T>& x, F&& f) {
    f(x.instances, x.tree.nodes, x.tree.order);
}
}  // namespace rt::ch10

#if RT_RPC_DEFINES_STUBS
namespace rt::ch10 {
template <class T>
ray<T> transform_ray(const affine3<T>& m, const ray<T>& r) {
    return RT_RPC_FORWARD(transform_ray, m, r);
}
template <class T>
vec3<T> transform_normal(const placement<T>& p, const vec3<T>& n) {
    return RT_RPC_FORWARD(transform_normal, p, n);
}
template <class T>
ch08::aabb<T> instance_box(const affine3<T>& to_world, const ch08::aabb<T>& box) {
    return RT_RPC_FORWARD(instance_box, to_world, box);
}
template <class T>
std::optional<hit_record<T>> instance_hit(const instance<T>& inst, const model_intersector<T>& model_hit,
                                          const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD_SERVED(std::optional<hit_record<T>>, instance_hit, model_hit, r, inst, served, r, range);
}
template <class T>
std::optional<hit_record<T>> closest_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit,
                                         const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD_SERVED(std::optional<hit_record<T>>, closest_hit, model_hit, r, scene, served, r, range);
}
template <class T>
bool any_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit, const ray<T>& r,
             const interval<T>& range) {
    return RT_RPC_FORWARD_SERVED(bool, any_hit, model_hit, r, scene, served, r, range);
}
}  // namespace rt::ch10
#endif

RT_RPC_FUNCTION(rt::ch10, transform_ray)
RT_RPC_FUNCTION(rt::ch10, transform_normal)
RT_RPC_FUNCTION(rt::ch10, instance_box)
RT_RPC_FUNCTION(rt::ch10, instance_hit)
RT_RPC_FUNCTION(rt::ch10, closest_hit)
RT_RPC_FUNCTION(rt::ch10, any_hit)
