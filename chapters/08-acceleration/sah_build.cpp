// sah_build.cpp — YOUR CODE for chapter 08, exercise 3: building the tree
// with the surface area heuristic. See bvh.hpp for the contract,
// median_build.hpp for a simpler builder to start from, and README.md
// ("Building the tree", "The expected cost of a split") for the lecture.
#include "bvh.hpp"

#include "common/stub.hpp"

namespace rt::ch08 {

template <class T>
bvh<T> build_sah(const std::vector<aabb<T>>& boxes, const build_options& options) {
    // Like build_median, top down, but at each node: bin the objects by
    // their box centres along each axis, sweep the bins once from each side
    // to get the areas and counts left and right of every plane, keep the
    // cheapest plane, and compare it with the cost of making a leaf.
    (void)boxes;
    (void)options;
    RT_NOT_IMPLEMENTED("chapter 08", "build_sah");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template bvh<float> build_sah(const std::vector<aabb<float>>&, const build_options&);
template bvh<double> build_sah(const std::vector<aabb<double>>&, const build_options&);

}  // namespace rt::ch08
