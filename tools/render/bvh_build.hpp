// bvh_build.hpp — the renderer's bounding volume hierarchy: a binary tree
// of float boxes, built with the binned surface area heuristic on every core.
//
// Chapter 08 teaches the tree (its slab test, traversal and SAH build are the
// students' exercises); this is the instructor-side version tuned for size:
// 48 million spheres must build in seconds and fit in memory. So:
//   * nodes are 32 bytes (a float box and two integers), both children of a
//     node are stored side by side, so a node names only its first child;
//   * the build moves compact 32-byte records (box + object number), not
//     indices into a far-away array, so each pass reads memory in order;
//   * big nodes bin their objects in parallel chunks, and once a node is
//     small enough its whole subtree is one task; tasks run on the
//     project's thread pool (rt::for_each_row), each writing its nodes
//     straight into the tree's array;
//   * the big arrays are big_vectors (common/big_array.hpp): in 2 MB pages,
//     and not zeroed before the build writes them.
// The boxes are the caller's: they must enclose each object as the renderer
// will test it (in float, rounding included), see fast_path.cpp.
#pragma once

#include "common/big_array.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

namespace rt::render_tool {

struct bvh_box {
    float lo[3], hi[3];
};

// The float box around the double box [lo, hi] widened by pad on every side:
// each corner rounded outwards (the largest float at or below lo - pad, the
// smallest at or above hi + pad), so the float box holds the double one
// whatever the rounding. V: anything indexed [0..2] (vec3d, double[3]).
inline float float_at_or_below(double x) {
    const float f = float(x);  // the nearest float: one step down if it landed above x
    // The step down, as std::nextafter(f, -infinity) but without a call or
    // a branch (half the roundings land above, at random: 48 million
    // spheres' boxes paid a mispredicted branch for every other corner).
    // A float's bits, read as a signed integer, step down by one for a
    // positive value and up by one for a negative one; zero steps from -0
    // to minus the smallest subnormal. (f = +infinity steps to the largest
    // float, still at or below x; NaN stays NaN through the comparison.)
    const float from = f == 0.0f ? -0.0f : f;
    std::int32_t bits;
    std::memcpy(&bits, &from, sizeof bits);
    bits += bits >= 0 ? -1 : 1;
    float below;
    std::memcpy(&below, &bits, sizeof below);
    return double(f) > x ? below : f;
}
inline float float_at_or_above(double x) { return -float_at_or_below(-x); }
template <class V>
bvh_box float_box_around(const V& lo, const V& hi, double pad) {
    bvh_box b;
    for (int a = 0; a < 3; ++a) b.lo[a] = float_at_or_below(lo[a] - pad), b.hi[a] = float_at_or_above(hi[a] + pad);
    return b;
}

struct bvh_node {
    bvh_box box;
    std::uint32_t first;  // leaf: first object in `order`; inner: index of the left child (right is first + 1)
    std::uint32_t count;  // leaf: number of objects (>= 1); inner: 0
};
static_assert(sizeof(bvh_node) == 32, "two nodes per cache line");

struct bvh_tree {
    // nodes[0] is the root (when there is any object). A tree of more than
    // 2^17 objects, built by tasks on several cores, may hold unused slots
    // between the tasks' nodes: walk it from the root, not as a list.
    big_vector<bvh_node> nodes;
    big_vector<std::uint32_t> order;   // the objects, leaf by leaf
    double build_seconds = 0;
    size_t leaves = 0, depth = 0;
    size_t bytes() const { return nodes.size() * sizeof(bvh_node) + order.size() * sizeof(std::uint32_t); }
};

// How deep a tree can be, which sizes every walk's stack. The SAH splits
// nodes down to bvh_max_sah_depth levels (not reached on any scene tried:
// 48 million spheres give 35, and 200 boxes each two thirds the size and
// distance of the last, as deep a chain as float's range holds, give 41);
// below that a node is halved by count, and a tree holds at most
// 2^bvh_max_objects_log2 objects.
inline constexpr size_t bvh_max_sah_depth = 100;
inline constexpr int bvh_max_objects_log2 = 30;
inline constexpr size_t bvh_max_depth = bvh_max_sah_depth + size_t(bvh_max_objects_log2);
// A binary tree's depth-first walk keeps at most one waiting child a level
// (the one not walked next) and the root.
inline constexpr size_t bvh_binary_walk_stack = bvh_max_depth + 2;

// Builds the tree over `count` objects, object i in the box box_of(i)
// (asked once per object, from every core: it must be safe to call from
// several threads at once; the boxes go straight into the build's records,
// with no array of their own). max_leaf: the largest leaf; smaller leaves
// are made whenever the SAH says splitting is cheaper.
bvh_tree build_bvh(size_t count, const std::function<bvh_box(size_t)>& box_of, int max_leaf = 8);
inline bvh_tree build_bvh(const std::vector<bvh_box>& boxes, int max_leaf = 8) {
    return build_bvh(boxes.size(), [&](size_t i) { return boxes[i]; }, max_leaf);
}

// The same tree with eight children per node: each wide node is a binary
// node and its descendants, opened largest box first until there are
// eight. Why: one ray then tests eight boxes at once (one vector of eight
// floats per box side) and walks about a third as many levels, and the
// eight boxes are stored side by side, each coordinate's eight values in
// one row (structure of arrays), so a node is four cache lines read in
// order. On a million small spheres the single rays of a packet part ways
// near the root, and then the number of levels and the bytes read per
// level are what a ray costs. The price: slots left empty where a subtree
// has fewer than eight leaves (the level-8 flake's tree is 1414 MB, 1170
// with four children).
inline constexpr int wide = 8;
struct alignas(64) bvh_wide_node {
    float lo[3][wide], hi[3][wide];  // box of child i: lo[axis][i] .. hi[axis][i]
    std::uint32_t child[wide];       // inner child: its node; leaf child: its first object
    std::uint32_t count[wide];       // leaf child: its number of objects; inner child: 0; no child: empty_slot
    static constexpr std::uint32_t empty_slot = 0xffffffffu;
};
static_assert(sizeof(bvh_wide_node) == 256, "four cache lines");

struct bvh_wide_tree {
    big_vector<bvh_wide_node> nodes;   // nodes[0] is the root (when there is any object)
    big_vector<std::uint32_t> order;   // the objects, leaf by leaf (the binary tree's order)
    double build_seconds = 0;           // the binary build and the collapse
    size_t leaves = 0, depth = 0;       // the binary tree's
    size_t bytes() const { return nodes.size() * sizeof(bvh_wide_node) + order.size() * sizeof(std::uint32_t); }
};

// Collapses a binary tree into a wide one (the binary nodes are freed).
bvh_wide_tree collapse_to_wide(bvh_tree&& binary);

}  // namespace rt::render_tool
