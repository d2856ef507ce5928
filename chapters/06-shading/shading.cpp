// shading.cpp — YOUR CODE for chapter 06. See shading.hpp for the contracts
// and README.md for the lecture. Suggested order: lambert, blinn_phong,
// shadow_ray_origin, shadow_ray, shade (each one's tests pass on its own).
#include "shading.hpp"

#include "common/stub.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rt::ch06 {

template <class T>
T lambert(const vec3<T>& normal, const vec3<T>& to_light) {
    // cos(theta) from the dot product of the two directions made unit length;
    // clamp at zero, and make an unusable input (zero length, NaN) give 0.
    (void)normal;
    (void)to_light;
    RT_NOT_IMPLEMENTED("chapter 06", "lambert");
}

template <class T>
T blinn_phong(const vec3<T>& normal, const vec3<T>& to_light, const vec3<T>& to_viewer, T shininess) {
    // Half vector of the unit light and viewer directions; its cosine with the
    // normal, raised to the shininess. Nothing when the light is below.
    (void)normal;
    (void)to_light;
    (void)to_viewer;
    (void)shininess;
    RT_NOT_IMPLEMENTED("chapter 06", "blinn_phong");
}

template <class T>
vec3<T> shadow_ray_origin(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_light) {
    // Step off the surface along the unit normal, towards the light's side,
    // by an offset that grows with the size of the point's coordinates.
    (void)point;
    (void)normal;
    (void)to_light;
    RT_NOT_IMPLEMENTED("chapter 06", "shadow_ray_origin");
}

template <class T>
shadow_query<T> shadow_ray(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& light_position) {
    // Origin from shadow_ray_origin, a unit direction to the light, and a
    // range that ends at the light.
    (void)point;
    (void)normal;
    (void)light_position;
    RT_NOT_IMPLEMENTED("chapter 06", "shadow_ray");
}

template <class T>
color shade(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_viewer, const material& m,
            const std::vector<point_light>& lights, const color& ambient, const occlusion_test<T>& occluded) {
    // Ambient, then for each light that is above the surface and not blocked:
    // (diffuse * Lambert + specular * Blinn-Phong) * intensity / distance^2.
    // The normal is already on the viewer's side: use it as given.
    (void)point;
    (void)normal;
    (void)to_viewer;
    (void)m;
    (void)lights;
    (void)ambient;
    (void)occluded;
    RT_NOT_IMPLEMENTED("chapter 06", "shade");
}

// Compile the exercise for both precisions. Leave these lines as they are.
template float lambert(const vec3<float>&, const vec3<float>&);
template double lambert(const vec3<double>&, const vec3<double>&);
template float blinn_phong(const vec3<float>&, const vec3<float>&, const vec3<float>&, float);
template double blinn_phong(const vec3<double>&, const vec3<double>&, const vec3<double>&, double);
template vec3<float> shadow_ray_origin(const vec3<float>&, const vec3<float>&, const vec3<float>&);
template vec3<double> shadow_ray_origin(const vec3<double>&, const vec3<double>&, const vec3<double>&);
template shadow_query<float> shadow_ray(const vec3<float>&, const vec3<float>&, const vec3<float>&);
template shadow_query<double> shadow_ray(const vec3<double>&, const vec3<double>&, const vec3<double>&);
template color shade(const vec3<float>&, const vec3<float>&, const vec3<float>&, const material&,
                     const std::vector<point_light>&, const color&, const occlusion_test<float>&);
template color shade(const vec3<double>&, const vec3<double>&, const vec3<double>&, const material&,
                     const std::vector<point_light>&, const color&, const occlusion_test<double>&);

}  // namespace rt::ch06
