// scene_tree.hpp — a whole scene through the tree: the closest hit and the
// shadow test of chapter 03's loop, answered by chapter 08's bvh instead.
//
// Chapter 08's program and rt-render's general path (--general) both draw a
// scene this way, so it is written once here. It is given code, not an
// exercise: it only splits the scene and calls the exercises (build_sah,
// closest_hit, any_hit) and the scene's one dispatch
// (common/object_dispatch.hpp).
//
// Every sphere and triangle goes into the tree. Planes have no finite box,
// so they stay outside it and are asked one by one, as in chapter 03.
#pragma once

#include "aabb.hpp"
#include "bvh.hpp"

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"
#include "common/scene.hpp"

#include <cmath>
#include <optional>
#include <vector>

namespace rt::ch08 {

// The scene split in two: what has a finite box goes into the tree; planes
// are tested one by one. bounded[k] is the scene's number of the tree's
// object k, in increasing order, so the tree's "lowest index wins" is the
// scene's too.
template <class T>
struct scene_tree {
    std::vector<int> bounded;
    std::vector<int> planes;
    bvh<T> tree;
};

// Splits the scene and builds the tree over its bounded objects (build_sah).
template <class T>
scene_tree<T> build_scene_tree(const scene<T>& world) {
    scene_tree<T> a;
    std::vector<aabb<T>> boxes;
    for (int i = 0; i < world.object_count(); ++i) {
        const object_ref o = locate(world, i);
        if (o.kind == shape_kind::plane) {
            a.planes.push_back(i);
            continue;
        }
        a.bounded.push_back(i);
        boxes.push_back(o.kind == shape_kind::sphere ? bounds(world.spheres[o.index])
                                                     : bounds(world.triangles[o.index]));
    }
    a.tree = build_sah(boxes);
    return a;
}

// The tree's leaf test: the tree's object k is the scene's bounded[k].
// `dispatch` answers dispatch.object_hit(i, r, range, hit) for scene object
// i (rt::object_dispatch does); it must outlive the returned function.
template <class T, class Dispatch>
leaf_intersector<T> leaf_test(const scene_tree<T>& a, const Dispatch& dispatch) {
    return [&a, &dispatch](int k, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) {
        return dispatch.object_hit(a.bounded[size_t(k)], r, range, hit);
    };
}

// The closest hit in range: the tree's, then the planes', the lowest scene
// number on equal t, exactly as chapter 03's loop over every object.
template <class T, class Dispatch>
std::optional<hit_record<T>> scene_closest_hit(const scene_tree<T>& a, const leaf_intersector<T>& leaf,
                                               const Dispatch& dispatch, const ray<T>& r, const interval<T>& range) {
    std::optional<hit_record<T>> best = closest_hit(a.tree, leaf, r, range);
    if (best) best->object = a.bounded[size_t(best->object)];
    for (int p : a.planes) {
        // Up to and including the best t: a plane hit at that very t wins by a lower number.
        const T upper = best ? std::nextafter(best->t, infinity<T>) : range.max;
        hit_record<T> hit;
        if (dispatch.object_hit(p, r, interval<T>{range.min, upper}, hit) && (!best || hit.t < best->t || p < best->object))
            best = hit;
    }
    return best;
}

// Is anything hit in range? Planes first (there are few), then the tree.
template <class T, class Dispatch>
bool scene_any_hit(const scene_tree<T>& a, const leaf_intersector<T>& leaf, const Dispatch& dispatch, const ray<T>& r,
                   const interval<T>& range) {
    hit_record<T> hit;
    for (int p : a.planes)
        if (dispatch.object_hit(p, r, range, hit)) return true;
    return any_hit(a.tree, leaf, r, range);
}

}  // namespace rt::ch08
