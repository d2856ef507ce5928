// ch08_scenes.hpp — what chapter 08's tests share: small scenes of spheres
// and triangles, their boxes, the brute-force answer the tree must equal, and
// a checker of the promises every built tree makes (bvh.hpp, struct bvh).
//
// Brute force is chapter 03's closest_hit, called through its header: every
// object in the order 0, 1, 2, ..., the smallest t in the open range wins,
// and of equal t the lowest index. (In your build it is your own chapter 03;
// the autograder uses the reference one.) The objects are tested with
// chapter 02's sphere test and chapter 05's triangle test.
#pragma once

#include "08-acceleration/aabb.hpp"
#include "08-acceleration/bvh.hpp"
#include "02-sphere/sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "05-triangle/triangle.hpp"

#include "common/hit_record.hpp"
#include "memory_bound.hpp"
#include "rpc/served.hpp"

#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace rt::ch08::test {

// Objects numbered spheres first, then triangles (as in a course scene).
template <class T>
struct objects {
    std::vector<sphere<T>> spheres;
    std::vector<triangle<T>> triangles;

    int count() const { return int(spheres.size() + triangles.size()); }

    std::vector<aabb<T>> boxes() const {
        std::vector<aabb<T>> b;
        for (const auto& s : spheres) b.push_back(bounds(s));
        for (const auto& t : triangles) b.push_back(bounds(t));
        return b;
    }

    // Object i's own test: its first hit in the range, or std::nullopt.
    std::optional<hit_record<T>> test(int i, const ray<T>& r, const interval<T>& range) const {
        const size_t k = size_t(i);
        if (k < spheres.size()) return ch02::intersect_sphere(spheres[k], r, range);
        return ch05::intersect_triangle(triangles[k - spheres.size()], r, range);
    }

    // The same in the form the tree asks it (leaf_intersector). It is a served
    // callback (tests/support/rpc/served.hpp): under the grader the grader's
    // own process answers each object your traversal asks about, with the
    // same test. `budget` limits how many objects one call may ask: the
    // grader keeps a record of the asks, and one beyond the budget makes the
    // traversal fail with rt::test::broken_rule, whatever it returns.
    leaf_intersector<T> intersector(long budget = -1) const { return served(budget); }

    // The same callback in chapter 03's form (object_intersector), for brute force.
    rt::test::served_objects<T> served(long budget = -1) const {
        rt::test::served_objects<T> s;
        s.count = count();
        s.test = [this](int i, const ray<T>& r, const interval<T>& range) { return test(i, r, range); };
        s.budget = budget;
        return s;
    }
};

// One call the tree made: which object, about which range, and what the test answered. The test's
// callback writes it down as it answers (under the grader, in the grader's own process), so a rule
// about the calls is checked from this record, whatever the traversal returns.
template <class T>
struct asked {
    int object = 0;
    interval<T> range{};
    std::optional<hit_record<T>> answer;
};
template <class T>
using call_record = std::shared_ptr<std::vector<asked<T>>>;

// The scene's callback, recording every call into `record`.
template <class T>
leaf_intersector<T> recording_intersector(const objects<T>& scene, const call_record<T>& record) {
    rt::test::served_objects<T> s = scene.served();
    s.test = [&scene, record](int i, const ray<T>& r, const interval<T>& range) {
        auto answer = scene.test(i, r, range);
        record->push_back({i, range, answer});
        return answer;
    };
    return s;
}

// build_sah under a bound on its memory derived from the number of objects (memory_bound.hpp): a
// tree of n objects has at most 2n - 1 nodes, so a build that keeps making nodes (a split that puts
// every object on one side is the same node again, split again forever) runs out of it at once and
// fails the same way on every run. The grader's runner builds under the same bound
// (tests/support/rpc/ch08.cpp).
inline constexpr const char* no_progress =
    "build_sah did not return a tree: it threw, or it used far more memory than a tree of these objects "
    "needs. A split must put at least one object on EACH side; a split with an empty side makes the node "
    "again, which is split the same way forever";

template <class T>
bvh<T> build_sah_bounded(const std::vector<aabb<T>>& boxes, const build_options& options = {}) {
    const rt::test::memory_bound bound(rt::test::tree_build_memory(boxes.size(), sizeof(bvh_node<T>)));
    try {
        return build_sah(boxes, options);
    } catch (const std::invalid_argument&) {
        throw;
    } catch (const std::exception&) {
        throw std::runtime_error(no_progress);
    }
}

// Brute force: chapter 03's closest_hit over every object.
template <class T>
std::optional<hit_record<T>> brute_force(const objects<T>& scene, const ray<T>& r, const interval<T>& range) {
    return ch03::closest_hit<T>(scene.count(), scene.served(), r, range);
}

// Bit-for-bit equality of two answers: both misses, or the same object and
// exactly the same bits of t, point and normal.
template <class T>
bool same_answer(const std::optional<hit_record<T>>& a, const std::optional<hit_record<T>>& b) {
    if (a.has_value() != b.has_value()) return false;
    if (!a) return true;
    return a->object == b->object && std::memcmp(&a->t, &b->t, sizeof(T)) == 0 &&
           std::memcmp(&a->point, &b->point, sizeof(a->point)) == 0 &&
           std::memcmp(&a->normal, &b->normal, sizeof(a->normal)) == 0;
}

template <class T>
vec3<T> random_point(std::mt19937_64& rng, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    return convert<T>(vec3d(u(rng), u(rng), u(rng)));
}

template <class T>
vec3<T> random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    vec3d v;
    do v = vec3d(n(rng), n(rng), n(rng));
    while (!(length(v) > 1e-3));
    return convert<T>(normalize(v));
}

// n spheres with centres in [-size, size]^3 and radii in [r_lo, r_hi].
template <class T>
void add_random_spheres(objects<T>& scene, std::mt19937_64& rng, int n, double size, double r_lo, double r_hi) {
    std::uniform_real_distribution<double> radius(r_lo, r_hi);
    for (int i = 0; i < n; ++i) scene.spheres.push_back({random_point<T>(rng, -size, size), T(radius(rng))});
}

// n small triangles scattered in [-size, size]^3, each corner within `spread` of the first.
template <class T>
void add_random_triangles(objects<T>& scene, std::mt19937_64& rng, int n, double size, double spread) {
    for (int i = 0; i < n; ++i) {
        const vec3<T> a = random_point<T>(rng, -size, size);
        scene.triangles.push_back(
            {a, a + random_point<T>(rng, -spread, spread), a + random_point<T>(rng, -spread, spread)});
    }
}

// A flat square grid of 2 n^2 triangles in the plane y = height, covering
// [-1, 1] x [-1, 1] in x and z: every triangle's box is flat, and neighbours
// share edges (a ray through an edge hits two triangles at the same t).
template <class T>
void add_planar_grid(objects<T>& scene, int n, T height) {
    const T step = T(2) / T(n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const T x0 = T(-1) + step * T(i), x1 = T(-1) + step * T(i + 1);
            const T z0 = T(-1) + step * T(j), z1 = T(-1) + step * T(j + 1);
            scene.triangles.push_back({{x0, height, z0}, {x0, height, z1}, {x1, height, z1}});
            scene.triangles.push_back({{x0, height, z0}, {x1, height, z1}, {x1, height, z0}});
        }
}

// A ray from a random point of [-size, size]^3 towards a random point of the
// same cube, so most rays cross the scene (and many start inside boxes).
template <class T>
ray<T> random_ray(std::mt19937_64& rng, double size) {
    const vec3<T> from = random_point<T>(rng, -size, size);
    vec3<T> to = random_point<T>(rng, -size, size);
    return {from, to - from};
}

// Checks the promises of struct bvh (bvh.hpp). Returns "" when they all hold,
// otherwise what is wrong, in words.
template <class T>
std::string tree_problem(const bvh<T>& tree, const std::vector<aabb<T>>& boxes, int max_leaf_size) {
    const size_t n = boxes.size();
    if (n == 0) return tree.nodes.empty() && tree.order.empty() ? "" : "a tree of no objects must have no nodes";
    if (tree.nodes.empty()) return "the tree has no nodes although there are objects";
    if (tree.order.size() != n) return "the object list does not hold each object exactly once (wrong length)";
    std::vector<int> seen_object(n, 0);
    for (int o : tree.order) {
        if (o < 0 || size_t(o) >= n) return "the object list holds an index that is not an object";
        if (seen_object[size_t(o)]++) return "an object appears twice in the object list";
    }
    std::vector<int> reached(tree.nodes.size(), 0);
    std::vector<int> leaf_owner(n, -1);  // which leaf holds each position of the list
    std::vector<int> todo{0};
    reached[0] = 1;
    while (!todo.empty()) {
        const int index = todo.back();
        todo.pop_back();
        const bvh_node<T>& node = tree.nodes[size_t(index)];
        aabb<T> expected;
        if (node.is_leaf()) {
            if (node.count > max_leaf_size) return "a leaf holds more objects than max_leaf_size";
            if (node.first < 0 || size_t(node.first) + size_t(node.count) > n)
                return "a leaf's run of objects lies outside the object list";
            for (int k = node.first; k < node.first + node.count; ++k) {
                if (leaf_owner[size_t(k)] >= 0) return "two leaves share a position of the object list";
                leaf_owner[size_t(k)] = index;
                expected.grow(boxes[size_t(tree.order[size_t(k)])]);
            }
        } else {
            if (node.count < 0) return "a node has a negative count";
            if (node.first <= index || size_t(node.first) + 1 >= tree.nodes.size())
                return "an interior node's children must come after it in the node list";
            for (int c : {node.first, node.first + 1}) {
                if (reached[size_t(c)]++) return "a node is reached twice from the root";
                todo.push_back(c);
                expected.grow(tree.nodes[size_t(c)].box);
            }
        }
        if (!(expected.lo == node.box.lo && expected.hi == node.box.hi))
            return "a node's box is not exactly the union of the boxes below it";
    }
    for (size_t k = 0; k < n; ++k)
        if (leaf_owner[k] < 0) return "an object is in no leaf: the split lost it";
    for (size_t i = 0; i < tree.nodes.size(); ++i)
        if (!reached[i]) return "a node is not reached from the root";
    return "";
}

}  // namespace rt::ch08::test
