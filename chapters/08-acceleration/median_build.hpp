// median_build.hpp — GIVEN: the simplest tree builder, so the traversal
// exercise can be done before the SAH build.
//
// Split every node with more than max_leaf_size objects in two halves: sort
// its objects along the axis where their box centres spread the most, and cut
// at the middle. It always makes a valid tree of depth about log2(N), but it
// ignores where the objects' surfaces are: a half may hold one huge object
// and many small ones, and its box then covers empty space that rays must
// still enter. The SAH builder (your exercise) fixes that (README, "Building
// the tree").
#pragma once

#include "bvh.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace rt::ch08 {

namespace detail {

template <class T>
aabb<T> union_of(const std::vector<aabb<T>>& boxes, const std::vector<int>& order, int first, int count) {
    aabb<T> b;
    for (int k = first; k < first + count; ++k) b.grow(boxes[size_t(order[size_t(k)])]);
    return b;
}

template <class T>
void split_at_median(bvh<T>& tree, const std::vector<aabb<T>>& boxes, int node_index, int max_leaf_size) {
    const int first = tree.nodes[size_t(node_index)].first;
    const int count = tree.nodes[size_t(node_index)].count;
    if (count <= max_leaf_size) return;  // stays a leaf

    // The axis along which the centres spread the most.
    aabb<T> centres;
    for (int k = first; k < first + count; ++k) centres.grow(boxes[size_t(tree.order[size_t(k)])].centroid());
    const vec3<T> extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);

    // Put the lower half of the centres first (ties broken by index, so the
    // tree does not depend on the standard library's partitioning).
    const int half = count / 2;
    auto begin = tree.order.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](int a, int b) {
        const T ca = boxes[size_t(a)].centroid()[axis], cb = boxes[size_t(b)].centroid()[axis];
        return ca < cb || (ca == cb && a < b);
    });

    const int left = int(tree.nodes.size());
    bvh_node<T> l, r;
    l.first = first;
    l.count = half;
    l.box = union_of(boxes, tree.order, first, half);
    r.first = first + half;
    r.count = count - half;
    r.box = union_of(boxes, tree.order, first + half, count - half);
    tree.nodes.push_back(l);
    tree.nodes.push_back(r);
    tree.nodes[size_t(node_index)].first = left;  // now an interior node
    tree.nodes[size_t(node_index)].count = 0;
    split_at_median(tree, boxes, left, max_leaf_size);
    split_at_median(tree, boxes, left + 1, max_leaf_size);
}

}  // namespace detail

// build_median — a tree with every property promised at struct bvh
// (bins is not used). Throws std::invalid_argument if max_leaf_size < 1.
template <class T>
bvh<T> build_median(const std::vector<aabb<T>>& boxes, const build_options& options = {}) {
    if (options.max_leaf_size < 1) throw std::invalid_argument("build_median: max_leaf_size must be at least 1");
    bvh<T> tree;
    const int n = int(boxes.size());
    if (n == 0) return tree;
    tree.order.resize(size_t(n));
    for (int i = 0; i < n; ++i) tree.order[size_t(i)] = i;
    tree.nodes.reserve(size_t(2 * n - 1));  // a binary tree with n leaves at most has 2n - 1 nodes
    bvh_node<T> root;
    root.first = 0;
    root.count = n;
    root.box = detail::union_of(boxes, tree.order, 0, n);
    tree.nodes.push_back(root);
    detail::split_at_median(tree, boxes, 0, options.max_leaf_size);
    return tree;
}

}  // namespace rt::ch08
