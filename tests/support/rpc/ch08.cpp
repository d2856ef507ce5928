// Chapter 08's exercise functions for the judge and the runner (table_builds.hpp explains the two halves).
// A tree argument travels whole (its nodes and order) only when it is not the tree this judge sent to
// this runner last (the tests ask hundreds of rays through one tree); the leaf intersector travels as
// a number: the judge answers each object the student's traversal asks about (served_by_judge.hpp) with
// the object's own test, and its record of those calls decides the test's rules (served.hpp).
#include "08-acceleration/bvh.hpp"
#include "served_by_judge.hpp"
#include "table_builds.hpp"

#include "ch08_fields.hpp"

namespace rt::ch08 {
template <class T, class F>
void fields(bvh<T>& x, F&& f) {
    f(x.nodes, x.order);
}
template <class F>
void fields(build_options& x, F&& f) {
    f(x.max_leaf_size, x.bins);
}

// A tree on the wire: a byte, 1 for "the tree I sent you last" (judge to runner only), or 0 and the
// tree. build_sah's result (runner to judge) is always whole.
#if defined(RT_RPC_JUDGE)
template <class T>
void put(rpc::writer& w, const bvh<T>& tree) {
    static std::optional<std::pair<std::uint64_t, bvh<T>>> last;  // (runner, tree) of the last tree sent
    const auto same = [](const bvh<T>& a, const bvh<T>& b) {
        return a.order == b.order && a.nodes.size() == b.nodes.size() &&
               std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(bvh_node<T>)) == 0;
    };
    if (last && last->first == rpc::runner_generation() && same(last->second, tree)) {
        rpc::put(w, std::uint8_t(1));
        return;
    }
    rpc::put(w, std::uint8_t(0));
    rpc::put(w, tree.nodes);
    rpc::put(w, tree.order);
    last.emplace(rpc::runner_generation(), tree);
}
template <class T>
void get(rpc::reader& r, bvh<T>& tree) {
    std::uint8_t whole = 1;
    rpc::get(r, whole);
    if (whole != 0) throw rpc::protocol_error("a tree answered as 'the one sent last'");
    rpc::get(r, tree.nodes);
    rpc::get(r, tree.order);
}
#elif defined(RT_RPC_RUNNER)
template <class T>
void get(rpc::reader& r, bvh<T>& tree) {
    static std::optional<bvh<T>> last;  // the last tree the judge sent whole
    std::uint8_t kind = 2;
    rpc::get(r, kind);
    if (kind == 1) {
        if (!last) throw rpc::protocol_error("'the tree sent last' before any tree");
        tree = *last;
        return;
    }
    if (kind != 0) throw rpc::protocol_error("a tree that is neither whole nor the last one");
    rpc::get(r, tree.nodes);
    rpc::get(r, tree.order);
    last = tree;
}
template <class T>
void put(rpc::writer& w, const bvh<T>& tree) {
    rpc::put(w, std::uint8_t(0));
    rpc::put(w, tree.nodes);
    rpc::put(w, tree.order);
}
#endif
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
    return RT_RPC_FORWARD_SERVED(std::optional<hit_record<T>>, closest_hit, intersect, r, tree, served, r, range);
}
template <class T>
bool any_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r, const interval<T>& range) {
    return RT_RPC_FORWARD_SERVED(bool, any_hit, intersect, r, tree, served, r, range);
}
}  // namespace rt::ch08
#endif

RT_RPC_FUNCTION(rt::ch08, intersect_box)
#if defined(RT_RPC_RUNNER)
// The runner builds under the same bound on memory as the tests (ch08_scenes.hpp, build_sah_bounded):
// a build that makes no progress fails at once, the same way on every run.
#include "memory_bound.hpp"
namespace rt::ch08 {
template <class T>
bvh<T> bounded_build_sah(const std::vector<aabb<T>>& boxes, const build_options& options) {
    const rt::test::memory_bound bound(rt::test::tree_build_memory(boxes.size(), sizeof(bvh_node<T>)));
    return build_sah(boxes, options);
}
}  // namespace rt::ch08
static const bool rt_rpc_served_build_sah =
    ::rt::rpc::serve(RT_RPC_CHAPTER "::build_sah<float>", &rt::ch08::bounded_build_sah<float>) &&
    ::rt::rpc::serve(RT_RPC_CHAPTER "::build_sah<double>", &rt::ch08::bounded_build_sah<double>);
#else
RT_RPC_FUNCTION(rt::ch08, build_sah)
#endif
RT_RPC_FUNCTION(rt::ch08, closest_hit)
RT_RPC_FUNCTION(rt::ch08, any_hit)
