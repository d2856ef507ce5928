// traversal.cpp — YOUR CODE for chapter 08, exercise 2: walking the tree.
// See bvh.hpp for the contract and README.md ("Closest hit", "Ties",
// "Any hit") for the lecture.
#include "bvh.hpp"

#include "common/stub.hpp"

namespace rt::ch08 {

template <class T>
std::optional<hit_record<T>> closest_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r,
                                         const interval<T>& range) {
    // A stack of nodes still to visit, starting with the root if the ray
    // enters its box. Pop a node; skip it if its entry is beyond the best hit
    // so far; at a leaf ask each object (up to and including the best t, for
    // ties); at an interior node test both children's boxes and push the
    // farther one first, so the nearer one is visited first.
    (void)tree;
    (void)intersect;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 08", "closest_hit");
}

template <class T>
bool any_hit(const bvh<T>& tree, const leaf_intersector<T>& intersect, const ray<T>& r, const interval<T>& range) {
    // The same walk without order and without shrinking the range: return
    // true at the first object hit.
    (void)tree;
    (void)intersect;
    (void)r;
    (void)range;
    RT_NOT_IMPLEMENTED("chapter 08", "any_hit");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template std::optional<hit_record<float>> closest_hit(const bvh<float>&, const leaf_intersector<float>&,
                                                      const ray<float>&, const interval<float>&);
template std::optional<hit_record<double>> closest_hit(const bvh<double>&, const leaf_intersector<double>&,
                                                       const ray<double>&, const interval<double>&);
template bool any_hit(const bvh<float>&, const leaf_intersector<float>&, const ray<float>&, const interval<float>&);
template bool any_hit(const bvh<double>&, const leaf_intersector<double>&, const ray<double>&,
                      const interval<double>&);

}  // namespace rt::ch08
