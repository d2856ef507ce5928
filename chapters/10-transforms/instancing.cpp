// instancing.cpp — YOUR CODE for chapter 10, exercises 4 and 5: the hit of
// one instance, and the two-level tree's closest hit and any hit. See
// instancing.hpp for the contracts and README.md ("The hit of an instance",
// "Two levels") for the lecture.
#include "instancing.hpp"

#include "common/stub.hpp"

namespace rt::ch10 {

template <class T>
std::optional<hit_record<T>> instance_hit(const instance<T>& inst, const model_intersector<T>& model_hit,
                                          const ray<T>& r, const interval<T>& range) {
    // Into the model's space with transform_ray(inst.place.to_object, r); ask
    // the model once, with the same range; bring the hit back (t as it is,
    // the point by to_world, the normal by transform_normal, the object
    // number offset by inst.first_object).
    (void)inst;
    (void)model_hit;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 10", "instance_hit");
}

template <class T>
std::optional<hit_record<T>> closest_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit,
                                         const ray<T>& r, const interval<T>& range) {
    // Chapter 08's closest_hit over scene.tree, with a leaf test that asks
    // instance_hit for instance k. Chapter 08 sets the answer's object to k:
    // remember the scene object number each instance's hit had, and put the
    // winner's back.
    (void)scene;
    (void)model_hit;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 10", "closest_hit");
}

template <class T>
bool any_hit(const instance_tree<T>& scene, const model_intersector<T>& model_hit, const ray<T>& r,
             const interval<T>& range) {
    // Chapter 08's any_hit over scene.tree, the leaf asking instance_hit.
    (void)scene;
    (void)model_hit;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 10", "any_hit");
}

// Compile the exercises for both precisions. Leave these lines as they are.
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
