// instancing.cpp — reference solution for chapter 10: one instance's hit and
// the two-level tree.
#include "10-transforms/instancing.hpp"

#include <utility>
#include <vector>

namespace rt::ch10 {

template <class T>
std::optional<hit_record<T>> instance_hit(const instance<T>& inst, const model_intersector<T>& model_hit,
                                          const ray<T>& r, const interval<T>& range) {
    // The direction stays unnormalised, so the model's t is the world's t and
    // the range needs no change.
    const ray<T> object_ray = transform_ray(inst.place.to_object, r);
    const std::optional<hit_record<T>> h = model_hit(inst.model, object_ray, range);
    if (!h) return std::nullopt;
    hit_record<T> world;
    world.t = h->t;
    world.point = transform_ray(inst.place.to_world, ray<T>{h->point, vec3<T>(0)}).origin;
    world.normal = transform_normal(inst.place, h->normal);
    world.object = inst.first_object + h->object;
    return world;
}

namespace {

// Chapter 08's leaf test reports the hit with object = the instance's index.
// The scene's object number of each instance's hit is kept here, so the
// winner's can be put back: the last hit an instance reported is the one
// chapter 08 kept for it (a later call about the same instance only comes
// with a narrower range, and it reports a hit only if it is nearer).
struct hits_seen {
    std::vector<std::pair<int, int>> by_instance;  // (instance, scene object number), in the order found

    int object_of(int instance) const {
        for (auto it = by_instance.rbegin(); it != by_instance.rend(); ++it)
            if (it->first == instance) return it->second;
        return -1;  // unreachable: the winner was seen
    }
};

template <class T>
ch08::leaf_intersector<T> instance_leaf(const instance_tree<T>& scene, const model_intersector<T>& model_hit,
                                        hits_seen* seen) {
    return [&scene, &model_hit, seen](int k, const ray<T>& r, const interval<T>& range, hit_record<T>& hit) {
        const std::optional<hit_record<T>> h = instance_hit(scene.instances[size_t(k)], model_hit, r, range);
        if (!h) return false;
        hit = *h;
        if (seen) seen->by_instance.emplace_back(k, h->object);
        return true;
    };
}

}  // namespace

template <class T>
std::optional<hit_record<T>> closest_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit,
                                         const ray<T>& r, const interval<T>& range) {
    hits_seen seen;
    std::optional<hit_record<T>> best = ch08::closest_hit(scene.tree, instance_leaf(scene, model_hit, &seen), r, range);
    // Chapter 08 breaks ties by the lowest instance, and each model by its
    // lowest object: with instances in the scene's order, that is the lowest
    // scene object number.
    if (best) best->object = seen.object_of(best->object);
    return best;
}

template <class T>
bool any_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit, const ray<T>& r,
             const interval<T>& range) {
    return ch08::any_hit(scene.tree, instance_leaf<T>(scene, model_hit, nullptr), r, range);
}

template std::optional<hit_record<float>> instance_hit(const instance<float>&, const model_intersector<float>&,
                                                       const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> instance_hit(const instance<double>&, const model_intersector<double>&,
                                                        const ray<double>&, const interval<double>&);
template std::optional<hit_record<float>> closest_hit(const instance_tree<float>&, const model_intersector<float>&,
                                                      const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> closest_hit(const instance_tree<double>&, const model_intersector<double>&,
                                                       const ray<double>&, const interval<double>&);
template bool any_hit(const instance_tree<float>&, const model_intersector<float>&, const ray<float>&,
                      const interval<float>&);
template bool any_hit(const instance_tree<double>&, const model_intersector<double>&, const ray<double>&,
                      const interval<double>&);

}  // namespace rt::ch10
