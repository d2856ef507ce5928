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
//     project's thread pool (rt::for_each_row).
// The boxes are the caller's: they must enclose each object as the renderer
// will test it (in float, rounding included), see fast_path.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rt::render_tool {

struct bvh_box {
    float lo[3], hi[3];
};

struct bvh_node {
    bvh_box box;
    std::uint32_t first;  // leaf: first object in `order`; inner: index of the left child (right is first + 1)
    std::uint32_t count;  // leaf: number of objects (>= 1); inner: 0
};
static_assert(sizeof(bvh_node) == 32, "two nodes per cache line");

struct bvh_tree {
    std::vector<bvh_node> nodes;        // nodes[0] is the root (when there is any object)
    std::vector<std::uint32_t> order;   // the objects, leaf by leaf
    double build_seconds = 0;
    size_t leaves = 0, depth = 0;
    size_t bytes() const { return nodes.size() * sizeof(bvh_node) + order.size() * sizeof(std::uint32_t); }
};

// Builds the tree over `boxes` (object i has box i). max_leaf: the largest
// leaf; smaller leaves are made whenever the SAH says splitting is cheaper.
bvh_tree build_bvh(const std::vector<bvh_box>& boxes, int max_leaf = 8);

// The same tree with four children per node: each wide node is a binary
// node and its children and grandchildren, opened largest box first until
// there are four. Why: one ray then tests four boxes at once (one vector
// of four floats per box side) and walks half as many levels, and the four
// boxes are stored side by side, each coordinate's four values in one row
// (structure of arrays), so a node is two cache lines read in order. On a
// million small spheres the single rays of a packet part ways near the
// root, and then the number of levels and the bytes read per level are
// what a ray costs.
inline constexpr int wide = 4;
struct alignas(64) bvh_wide_node {
    float lo[3][wide], hi[3][wide];  // box of child i: lo[axis][i] .. hi[axis][i]
    std::uint32_t child[wide];       // inner child: its node; leaf child: its first object
    std::uint32_t count[wide];       // leaf child: its number of objects; inner child: 0; no child: empty_slot
    static constexpr std::uint32_t empty_slot = 0xffffffffu;
};
static_assert(sizeof(bvh_wide_node) == 128, "two cache lines");

struct bvh_wide_tree {
    std::vector<bvh_wide_node> nodes;   // nodes[0] is the root (when there is any object)
    std::vector<std::uint32_t> order;   // the objects, leaf by leaf (the binary tree's order)
    double build_seconds = 0;           // the binary build and the collapse
    size_t leaves = 0, depth = 0;       // the binary tree's
    size_t bytes() const { return nodes.size() * sizeof(bvh_wide_node) + order.size() * sizeof(std::uint32_t); }
};

// Collapses a binary tree into a wide one (the binary nodes are freed).
bvh_wide_tree collapse_to_wide(bvh_tree&& binary);

}  // namespace rt::render_tool
