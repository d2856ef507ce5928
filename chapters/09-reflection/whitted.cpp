// whitted.cpp — YOUR CODE for chapter 09, part 3. See whitted.hpp for the
// contract and README.md ("Recursion") for the lecture. It uses parts 1 and
// 2: do them first.
#include "whitted.hpp"

#include "common/stub.hpp"

#include <algorithm>
#include <stdexcept>

namespace rt::ch09 {

template <class T>
color trace(const scene<T>& world, const ray<T>& r, const interval<T>& range, int depth, float throughput) {
    // Find and light the hit (closest_surface_hit, local_light); then, while
    // depth allows and the throughput is worth it, add the mirror's reflected
    // ray, or glass's reflected and refracted rays weighted by Fresnel.
    (void)world;
    (void)r;
    (void)range;
    (void)depth;
    (void)throughput;
    RT_NOT_IMPLEMENTED("chapter 09", "trace");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template color trace(const scene<float>&, const ray<float>&, const interval<float>&, int, float);
template color trace(const scene<double>&, const ray<double>&, const interval<double>&, int, float);

}  // namespace rt::ch09
