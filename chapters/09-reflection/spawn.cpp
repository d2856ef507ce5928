// spawn.cpp — YOUR CODE for chapter 09, part 2. See spawn.hpp for the
// contract and README.md ("Where a secondary ray starts") for the lecture.
#include "spawn.hpp"

#include "common/stub.hpp"

#include <cmath>
#include <limits>

namespace rt::ch09 {

template <class T>
vec3<T> offset_ray_origin(const surface_point<T>& p, const vec3<T>& n, const vec3<T>& w) {
    // Project the error box on the normal, push along n to the side w leaves
    // by, then step each moved component one float further.
    (void)p;
    (void)n;
    (void)w;
    RT_NOT_IMPLEMENTED("chapter 09", "offset_ray_origin");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template vec3<float> offset_ray_origin(const surface_point<float>&, const vec3<float>&, const vec3<float>&);
template vec3<double> offset_ray_origin(const surface_point<double>&, const vec3<double>&, const vec3<double>&);

}  // namespace rt::ch09
