// bvh.hpp — the bounding volume hierarchy: the tree, how to build it, how to
// walk it. Chapter 08's second and third exercises are contracts here:
//   build_sah    (sah_build.cpp)   the surface area heuristic with binning
//   closest_hit  (traversal.cpp)   the nearest hit, equal to brute force's
//   any_hit      (traversal.cpp)   "is anything hit?", for shadow rays
// The tree itself, its cost and a median-split builder (median_build.hpp)
// are given, so the traversal can be written and tested before the SAH build.
// README.md is the lecture.
//
// The tree knows nothing about spheres or triangles: it is built from one box
// per object and, to test an object, calls the scene's own dispatch
// intersect(i, r, range, hit) (rt::object_dispatch::object_hit in common/object_dispatch.hpp has that form).
// Objects are numbered 0 .. N-1 as in chapter 03.
#pragma once

#include "aabb.hpp"

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"

#include <functional>
#include <optional>
#include <vector>

namespace rt::ch08 {

// How the tree asks "does the ray hit object i inside this range?":
// intersect(i, r, range, hit) returns true when object i is hit with
// range.min < t < range.max, and then `hit` holds that hit, the first one in
// the range (the object's smallest t there), with hit.object = i. The t it
// reports for a hit must not depend on range.max (true of every chapter's
// shape test). rt::object_dispatch::object_hit (common/object_dispatch.hpp) answers it.
template <class T>
using leaf_intersector = std::function<bool(int object, const ray<T>& r, const interval<T>& range, hit_record<T>& hit)>;

// One node of the tree. Children are stored side by side: an interior node's
// left child is nodes[first] and its right child nodes[first + 1]. A leaf owns
// a run of the tree's object list: order[first], ..., order[first + count - 1].
template <class T>
struct bvh_node {
    aabb<T> box;    // the smallest box holding the boxes of every object below
    int first = 0;  // leaf: first position in bvh::order; interior: index of the left child
    int count = 0;  // leaf: how many objects (at least 1); interior: 0

    bool is_leaf() const { return count > 0; }
};

// A built tree. What every builder promises (and the tests check):
//   * no objects: no nodes and an empty order;
//   * otherwise nodes[0] is the root; order holds every object index exactly
//     once; every node is reached from the root exactly once; a child's index
//     is larger than its parent's;
//   * every node's box is exactly the union (componentwise min and max) of the
//     boxes of the objects below it, so it is exact, not an approximation;
//   * every leaf holds at least 1 and at most build_options::max_leaf_size objects.
template <class T>
struct bvh {
    std::vector<bvh_node<T>> nodes;
    std::vector<int> order;
};

struct build_options {
    int max_leaf_size = 4;  // a node with more objects is always split (>= 1)
    int bins = 16;          // SAH: candidate planes per axis = bins - 1 (>= 2)
};

// The cost model of the surface area heuristic (README, "The expected cost of
// a split"): a ray that reaches a node pays sah_traversal_cost to test its
// children's boxes, and sah_intersection_cost per object of a leaf. The
// probability that a ray which hits box P also hits box C inside it is
// area(C) / area(P) (for rays from everywhere, in every direction).
template <class T>
inline constexpr T sah_traversal_cost = T(1);
template <class T>
inline constexpr T sah_intersection_cost = T(1);

// sah_cost — the expected cost of a ray that hits the root box:
//     sum over interior nodes n of  sah_traversal_cost    * area(n) / area(root)
//   + sum over leaves l         of  sah_intersection_cost * count(l) * area(l) / area(root)
// (area = aabb::half_area; when the root's area is 0 every ratio counts as 1).
// Lower is better; the tests compare builders with it. 0 for an empty tree.
template <class T>
T sah_cost(const bvh<T>& tree) {
    if (tree.nodes.empty()) return T(0);
    const T root_area = tree.nodes[0].box.half_area();
    T cost = 0;
    for (const bvh_node<T>& n : tree.nodes) {
        const T p = root_area > T(0) ? n.box.half_area() / root_area : T(1);
        cost += n.is_leaf() ? sah_intersection_cost<T> * T(n.count) * p : sah_traversal_cost<T> * p;
    }
    return cost;
}

// build_sah — exercise: build the tree with the surface area heuristic.
//
// Inputs
//   boxes    boxes[i] bounds object i (every point where intersect(i, ...)
//            can report a hit lies in it). Boxes may be flat or points.
//   options  max_leaf_size and bins, as in build_options.
//
// Returns a tree with every property listed at struct bvh, built top down.
// For a node holding objects S with box B (area A):
//   * Candidate splits: for each axis whose CENTROID bounds (the box of the
//     objects' box centres) have a positive extent, the extent is cut into
//     options.bins equal bins; an object goes to bin
//         min(bins - 1, floor(bins * (centre - centroid_lo) / extent)),
//     and the bins - 1 planes between bins are the candidates. A candidate
//     puts the bins left of its plane in L and the rest in R; one with L or
//     R empty is not a candidate.
//   * Its cost is  sah_traversal_cost * A + sah_intersection_cost * (A_L |L| + A_R |R|),
//     A_L and A_R the areas of the unions of L's and R's boxes (the cost
//     above, multiplied through by A so that A = 0 needs no division).
//   * The node becomes a leaf when |S| <= max_leaf_size and no candidate is
//     cheaper than the leaf, sah_intersection_cost * |S| * A.
//   * Otherwise it is split by the cheapest candidate (any of equal cost).
//     If there is no candidate at all (every centre is the same point) and
//     |S| > max_leaf_size, S is cut into two halves of sizes floor(|S|/2)
//     and the rest, in any order, so that leaves never exceed max_leaf_size.
//   An empty `boxes` gives an empty tree.
//
// What the tests grade besides the tree's validity:
//   * cost: on scenes of a few clusters of small objects, and on a flat mesh,
//     sah_cost(your tree) < 0.8 * sah_cost(build_median's tree);
//   * progress: every split puts at least one object on each side. The tests
//     build under a bound on memory derived from the number of objects (a
//     tree of n objects has at most 2n - 1 nodes); a split with an empty side
//     is the node again, split the same way forever, and runs out of it at
//     once ("build_sah did not return a tree").
//
// Throws std::invalid_argument if max_leaf_size < 1 or bins < 2.
template <class T>
bvh<T> build_sah(const std::vector<aabb<T>>& boxes, const build_options& options = {});

// closest_hit — exercise: the nearest hit, found through the tree.
//
// Inputs
//   tree       a tree built (by any builder above) from boxes of these objects
//   intersect  tests one object (see leaf_intersector above)
//   r, range   the ray and the open interval (range.min, range.max) of t
//
// Returns EXACTLY what brute force (chapter 03's loop over all objects,
// 0, 1, 2, ...) returns: the hit with the smallest t in the open range,
// and among hits with exactly the same t the one of the LOWEST object index;
// the record is the one intersect filled in for that object (its `object`
// field is the object's index). std::nullopt when nothing is hit. (The tree
// visits objects in another order than 0, 1, 2, ..., so the lowest-index rule
// must be enforced, not inherited: README, "Ties".)
//
// How (the tests check the result, the README explains why each step is needed):
//   * A node whose box is missed, by intersect_box against
//     (range.min, t of the best hit so far), is skipped with all below it.
//   * Of two children, the one entered first (smaller entry) is visited
//     first; the other is visited afterwards only if its entry is still
//     <= widen_exit(best t found by then), the very comparison intersect_box
//     would make (an object's reported t can lie a rounding below its box's
//     entry: an unwidened comparison would lose it).
//   * In a leaf, every object is asked for hits up to and including the best
//     t so far (a hit at exactly that t can still win by a lower index).
//   * An empty tree is a miss, and intersect is never called.
//
// What the tests count, from the calls they answer (not from your answer):
//   * budget: along a row of objects, one per leaf, that the ray crosses,
//     nearest first with pruning asks the nearest object and almost nothing
//     else: the tests allow 3 asks for a row of 32 and 6 for a row of 64;
//   * order: there, the first object asked is the nearest one;
//   * shrinking: once an object has been hit at t, no object is asked about a
//     range reaching beyond the next number above t.
template <class T>
std::optional<hit_record<T>> closest_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r,
                                         const interval<T>& range);

// any_hit — exercise: is any object hit with range.min < t < range.max?
//
// Same inputs as closest_hit. Returns true exactly when closest_hit would
// return a hit. Stops at the first object hit it finds (in any order): a
// shadow ray only asks whether the light is blocked, never by what. (The
// tests check that no object is asked after one was hit.)
template <class T>
bool any_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r, const interval<T>& range);

}  // namespace rt::ch08
