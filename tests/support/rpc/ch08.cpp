// Chapter 08's exercise functions for the judge and the runner (table.hpp explains the two halves).
// The tree travels whole (its nodes and order); the leaf intersector travels as the table of hits the
// test's callback stands for along the call's ray, and is answered in the runner (served.hpp).
#include "08-acceleration/bvh.hpp"
#include "served_wire.hpp"
#include "table.hpp"

namespace rt::ch08 {
// The chapter's structs travel like the course's others (wire.hpp).
template <class T, class F>
void fields(aabb<T>& x, F&& f) {
    f(x.lo, x.hi);
}
template <class T, class F>
void fields(bvh_node<T>& x, F&& f) {
    f(x.box, x.first, x.count);
}
template <class T, class F>
void fields(bvh<T>& x, F&& f) {
    f(x.nodes, x.order);
}
template <class F>
void fields(build_options& x, F&& f) {
    f(x.max_leaf_size, x.bins);
}
}  // namespace rt::ch08

#if RT_RPC_DEFINES_STUBS
namespace rt::ch08 {
template <class T>
std::optional<T> intersect_box(const aabb<T>& box, const ray<T>& r, const vec3<T>& inv_direction,
                               const interval<T>& range) {
    return RT_RPC_FORWARD(intersect_box, box, r, inv_direction, range);
}
template <class T>
bvh<T> build_sah(const std::vector<aabb<T>>& boxes, const build_options& options) {
    return RT_RPC_FORWARD(build_sah, boxes, options);
}
template <class T>
std::optional<hit_record<T>> closest_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r,
                                         const interval<T>& range) {
    return RT_RPC_FORWARD_AS(std::optional<hit_record<T>>, closest_hit, tree, ::rt::rpc::served_for(intersect, r), r,
                             range);
}
template <class T>
bool any_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD_AS(bool, any_hit, tree, ::rt::rpc::served_for(intersect, r), r, range);
}
}  // namespace rt::ch08
#endif

RT_RPC_FUNCTION(rt::ch08, intersect_box)
RT_RPC_FUNCTION(rt::ch08, build_sah)
RT_RPC_FUNCTION(rt::ch08, closest_hit)
RT_RPC_FUNCTION(rt::ch08, any_hit)
