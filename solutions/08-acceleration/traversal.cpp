// traversal.cpp — reference solution for chapter 08: walking the tree.
#include "08-acceleration/bvh.hpp"

#include <cmath>

namespace rt::ch08 {

namespace {

// A node waiting on the stack, with the parameter at which the ray enters it
// (computed when its parent was visited), so it can be skipped without a
// second box test if a closer hit has been found in the meantime.
template <class T>
struct pending {
    int node;
    T entry;
};

// The deepest a tree can be is its number of nodes; a small fixed stack
// covers every balanced tree, and the vector grows only for a degenerate one.
constexpr size_t typical_depth = 64;

// Asks the objects of one leaf, keeping the nearest hit and, among hits at
// exactly the same t, the lowest object index (brute force's answer).
template <class T>
void visit_leaf(const bvh<T>& tree, const bvh_node<T>& leaf, const leaf_intersector<T>& intersect, const ray<T>& r,
                const interval<T>& range, std::optional<hit_record<T>>& best) {
    for (int k = leaf.first; k < leaf.first + leaf.count; ++k) {
        const int object = tree.order[size_t(k)];
        // Up to and INCLUDING the best t: the next representable number above
        // it is the open bound. Without it an object of lower index hit at
        // the same t would be missed whenever it is visited second.
        const T upper = best ? std::nextafter(best->t, infinity<T>) : range.max;
        hit_record<T> hit;
        if (!intersect(object, r, interval<T>{range.min, upper}, hit)) continue;
        if (!best || hit.t < best->t || object < best->object) {
            hit.object = object;
            best = hit;
        }
    }
}

}  // namespace

template <class T>
std::optional<hit_record<T>> closest_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r,
                                         const interval<T>& range) {
    std::optional<hit_record<T>> best;
    if (tree.nodes.empty()) return best;
    const vec3<T> inv = reciprocal(r.direction);
    auto box_entry = [&](int node) {
        // Only boxes entered no later than the best hit so far can hold a
        // better one (or an equal one of lower index).
        return intersect_box(tree.nodes[size_t(node)].box, r, inv, {range.min, best ? best->t : range.max});
    };

    const auto root = box_entry(0);
    if (!root) return best;
    std::vector<pending<T>> stack;
    stack.reserve(typical_depth);
    stack.push_back({0, *root});
    while (!stack.empty()) {
        const pending<T> p = stack.back();
        stack.pop_back();
        // Re-check: a hit found since this node was pushed may lie before its
        // entry. Widened exactly as intersect_box widens its exit, so this is
        // the box test against the new best, without redoing it.
        if (best && p.entry > widen_exit(best->t)) continue;
        const bvh_node<T>& n = tree.nodes[size_t(p.node)];
        if (n.is_leaf()) {
            visit_leaf(tree, n, intersect, r, range, best);
            continue;
        }
        const auto left = box_entry(n.first);
        const auto right = box_entry(n.first + 1);
        // Push the farther child first so the nearer one is popped (visited) first.
        if (left && right) {
            const bool left_first = *left <= *right;
            stack.push_back(left_first ? pending<T>{n.first + 1, *right} : pending<T>{n.first, *left});
            stack.push_back(left_first ? pending<T>{n.first, *left} : pending<T>{n.first + 1, *right});
        } else if (left) {
            stack.push_back({n.first, *left});
        } else if (right) {
            stack.push_back({n.first + 1, *right});
        }
    }
    return best;
}

template <class T>
bool any_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r, const interval<T>& range) {
    if (tree.nodes.empty()) return false;
    const vec3<T> inv = reciprocal(r.direction);
    // No ordering and no shrinking: the first hit anywhere answers the question.
    std::vector<int> stack;
    stack.reserve(typical_depth);
    stack.push_back(0);
    while (!stack.empty()) {
        const bvh_node<T>& n = tree.nodes[size_t(stack.back())];
        stack.pop_back();
        if (!intersect_box(n.box, r, inv, range)) continue;
        if (!n.is_leaf()) {
            stack.push_back(n.first);
            stack.push_back(n.first + 1);
            continue;
        }
        hit_record<T> hit;
        for (int k = n.first; k < n.first + n.count; ++k)
            if (intersect(tree.order[size_t(k)], r, range, hit)) return true;
    }
    return false;
}

template std::optional<hit_record<float>> closest_hit(const bvh<float>&, const leaf_intersector<float>&,
                                                      const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> closest_hit(const bvh<double>&, const leaf_intersector<double>&,
                                                       const ray<double>&, const interval<double>&);
template bool any_hit(const bvh<float>&, const leaf_intersector<float>&, const ray<float>&, const interval<float>&);
template bool any_hit(const bvh<double>&, const leaf_intersector<double>&, const ray<double>&,
                      const interval<double>&);

}  // namespace rt::ch08
