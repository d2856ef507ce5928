// spawn.cpp — reference solution for chapter 09's secondary-ray origin.
#include "09-reflection/spawn.hpp"

#include <cmath>
#include <limits>

namespace rt::ch09 {

template <class T>
vec3<T> offset_ray_origin(const surface_point<T>& p, const vec3<T>& n, const vec3<T>& w) {
    // How far along n the exact surface may lie from the computed point: the
    // error box projected on the normal.
    const T reach = std::fabs(n.x) * p.error.x + std::fabs(n.y) * p.error.y + std::fabs(n.z) * p.error.z;
    // Push to the side the new ray leaves by: a reflected ray stays on the
    // side it came from, a refracted one goes through.
    const vec3<T> offset = (dot(w, n) < T(0) ? -reach : reach) * n;
    vec3<T> o = p.point + offset;
    // The sum was rounded, perhaps back towards the surface: one more float
    // step away from it in every component that moved.
    for (int i = 0; i < 3; ++i) {
        if (offset[i] > T(0)) o[i] = std::nextafter(o[i], std::numeric_limits<T>::infinity());
        if (offset[i] < T(0)) o[i] = std::nextafter(o[i], -std::numeric_limits<T>::infinity());
    }
    return o;
}

template vec3<float> offset_ray_origin(const surface_point<float>&, const vec3<float>&, const vec3<float>&);
template vec3<double> offset_ray_origin(const surface_point<double>&, const vec3<double>&, const vec3<double>&);

}  // namespace rt::ch09
