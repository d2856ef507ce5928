// instancing.hpp — one object stored once, placed many times; chapter 10's
// second group of exercises:
//   instance_hit  (instancing.cpp)  the hit of one instance
//   closest_hit   (instancing.cpp)  the nearest hit through the two-level tree
//   any_hit       (instancing.cpp)  "is anything hit?" through it, for shadow rays
//
// A MODEL is anything that can answer "the closest hit of this ray, in my own
// space, in this range": a mesh in its own chapter 08 tree, one sphere, or a
// scene of instances itself (instances of instances). An INSTANCE places a
// model in the world by a transform. A scene of instances is the top level
// of a two-level tree: a chapter 08 bvh over the instances' world boxes, each
// leaf an instance, each instance a door into its model's own (bottom-level)
// tree. The models are stored once, however many instances place them.
// README.md, "Instancing", is the lecture.
#pragma once

#include "transform.hpp"

#include "08-acceleration/aabb.hpp"
#include "08-acceleration/bvh.hpp"

#include "common/hit_record.hpp"
#include "common/interval.hpp"
#include "common/ray.hpp"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rt::ch10 {

// How an instance asks its model for a hit: model_hit(model, r, range) is
// model number `model`'s closest hit of the ray r (in the model's own space)
// with range.min < t < range.max, or std::nullopt. The record's t is r's
// parameter, its point and normal are in the model's space (the normal unit
// length), and its `object` the number of the object hit among the model's
// own objects 0, 1, 2, ... (the lowest of them on equal t). Chapter 03's
// object_intersector has the same form: the model plays the object.
template <class T>
using model_intersector = std::function<std::optional<hit_record<T>>(int model, const ray<T>& r, const interval<T>& range)>;

// One placement of a model.
//   place         the transform to the world and its inverse (make_placement)
//   model         the model it places: model_intersector's first argument
//   first_object  the scene's number of the model's object 0 in this
//                 placement: the model's object j is the scene's object
//                 first_object + j. A scene built flat (every object copied
//                 out) numbers its objects the same way.
template <class T>
struct instance {
    placement<T> place;
    int model = 0;
    int first_object = 0;
};

// The top level of the two-level tree: the instances, in the scene's order
// (each instance's objects numbered after those of the instance before it),
// and a chapter 08 bvh over their world boxes (leaf object k is instances[k]).
template <class T>
struct instance_tree {
    std::vector<instance<T>> instances;
    ch08::bvh<T> tree;
};

// Builds the top-level tree (given): each instance's box is instance_box of
// its model's box (model_boxes[model], in the model's space), the tree is
// chapter 08's build_sah over them. Throws std::invalid_argument for an
// instance whose model has no box, or instances out of the scene's order.
template <class T>
instance_tree<T> build_instance_tree(std::vector<instance<T>> instances, const std::vector<ch08::aabb<T>>& model_boxes) {
    instance_tree<T> scene;
    std::vector<ch08::aabb<T>> boxes;
    for (size_t k = 0; k < instances.size(); ++k) {
        const instance<T>& inst = instances[k];
        if (inst.model < 0 || size_t(inst.model) >= model_boxes.size())
            throw std::invalid_argument("instance " + std::to_string(k) + " places model " + std::to_string(inst.model) +
                                        ", but the models are 0 .. " + std::to_string(int(model_boxes.size()) - 1));
        if (k > 0 && !(instances[k - 1].first_object < inst.first_object))
            throw std::invalid_argument("instance " + std::to_string(k) +
                                        ": instances must come in the order of their first_object");
        boxes.push_back(instance_box(inst.place.to_world, model_boxes[size_t(inst.model)]));
    }
    scene.tree = ch08::build_sah(boxes);
    scene.instances = std::move(instances);
    return scene;
}

// The box of a whole scene of instances (its root's box), for placing it as
// a model in turn. Empty for no instances.
template <class T>
ch08::aabb<T> scene_box(const instance_tree<T>& scene) {
    return scene.tree.nodes.empty() ? ch08::aabb<T>{} : scene.tree.nodes[0].box;
}

// instance_hit — exercise: the hit of one instance.
//
// Inputs
//   inst       the instance
//   model_hit  asks a model (see model_intersector)
//   r, range   the world ray and the open range (range.min, range.max) of t
//
// Does, in this order:
//   1. takes the ray into the model's space: object_ray =
//      transform_ray(inst.place.to_object, r), your first exercise, bit for
//      bit (its direction is not normalised, so t means the same there);
//   2. asks model_hit(inst.model, object_ray, range) exactly once, with the
//      range unchanged: because t is the same in both spaces, the range is
//      too (no rescaling, no clamping);
//   3. on a hit h, returns the record brought back to the world:
//        t       h.t, unchanged
//        point   inst.place.to_world applied to h.point (A p + b, computed
//                as transform_ray computes an origin)
//        normal  transform_normal(inst.place, h.normal)
//        object  inst.first_object + h.object
//      and std::nullopt on a miss.
// The tests answer model_hit themselves and check the one call it gets
// (its model, its ray, its range) from their own record of it.
template <class T>
std::optional<hit_record<T>> instance_hit(const instance<T>& inst, const model_intersector<T>& model_hit,
                                          const ray<T>& r, const interval<T>& range);

// closest_hit — exercise: the nearest hit of a scene of instances.
//
// Inputs
//   scene      the instances and their tree (build_instance_tree)
//   model_hit  asks a model, as in instance_hit
//   r, range   the world ray and the open range of t
//
// Returns the hit with the smallest t in the range over every instance, as
// instance_hit brings it back, and of equal t the one with the lowest scene
// object number (so: the lowest instance, then the model's own rule);
// std::nullopt when nothing is hit. Exactly the answer of asking every
// instance with instance_hit in turn, 0, 1, 2, ..., shrinking the range to
// the best t so far (chapter 03's loop), but through the tree:
//   * the top level is a chapter 08 tree whose objects are the instances:
//     chapter 08's closest_hit walks it, with a leaf test that asks
//     instance_hit (chapter 08's leaf sets hit.object to the instance's
//     number; the scene's object number must come back in the answer);
//   * an instance is asked only if the ray meets its box before the best hit
//     so far, and about the range up to (and including) that hit, so a model
//     never searches beyond what is already found.
// Bound (what the tests check, on scenes of spheres and triangles placed by
// affine maps, spheres by turns, scales and translations): the same object
// as the scene built flat (every object mapped to the world in double,
// rounded once to T), and
//     |t - t_flat| <= 16 epsilon t c,
// for rays meeting the surface at |cos| >= 0.2, where c is the largest of 1,
// the ray's distance from the object over its size (chapter 07: the sphere
// test loses digits with it) and the object's coordinates over the ray's
// length to the hit |t d| (the flat scene's own rounding). Measured largest
// ratio: README, "Rounding, measured".
// What the tests count, from the calls they answer: along a row of
// instances the ray crosses, nearest first with pruning asks almost only the
// nearest one; every ray a model is asked about is some instance's
// transform_ray(to_object, r), and each call's model is that instance's.
template <class T>
std::optional<hit_record<T>> closest_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit,
                                         const ray<T>& r, const interval<T>& range);

// any_hit — exercise: is anything hit with range.min < t < range.max?
//
// Same inputs as closest_hit. True exactly when closest_hit would return a
// hit; stops at the first instance hit (chapter 08's any_hit over the top
// level, the leaf asking instance_hit). The tests check that no model is
// asked after one answered with a hit.
template <class T>
bool any_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit, const ray<T>& r,
             const interval<T>& range);

}  // namespace rt::ch10
