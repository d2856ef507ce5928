// shading.cpp — reference solution for chapter 06.
#include "06-shading/shading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rt::ch06 {

namespace {

// Finite and not zero, written so that NaN fails it.
template <class T>
bool usable_direction(const vec3<T>& v) {
    return is_finite(v) && (v.x != T(0) || v.y != T(0) || v.z != T(0));
}

// v / |v| for a usable direction. Dividing by the largest component first
// keeps dot(v, v) from overflowing (a float vector of length 1e20) or
// underflowing to zero (length 1e-20) on the way.
template <class T>
vec3<T> unit(const vec3<T>& v) {
    const vec3<T> scaled = v / std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    return scaled / length(scaled);
}

// Cosine of the angle between a and b, or NaN when either is unusable.
// Making both unit length is what makes the answer depend on the angle only.
template <class T>
T cosine(const vec3<T>& a, const vec3<T>& b) {
    if (!usable_direction(a) || !usable_direction(b)) return std::numeric_limits<T>::quiet_NaN();
    return dot(unit(a), unit(b));
}

}  // namespace

template <class T>
T lambert(const vec3<T>& normal, const vec3<T>& to_light) {
    const T c = cosine(normal, to_light);
    // Written as "c > 0" so that NaN (an unusable input) gives 0 as well.
    return c > T(0) ? std::min(c, T(1)) : T(0);
}

template <class T>
T blinn_phong(const vec3<T>& normal, const vec3<T>& to_light, const vec3<T>& to_viewer, T shininess) {
    if (!(shininess >= T(0))) throw std::invalid_argument("blinn_phong: shininess must be >= 0");
    if (!(lambert(normal, to_light) > T(0))) return T(0);  // the light is below the surface
    if (!usable_direction(to_viewer)) return T(0);
    // The half vector bisects the angle between the unit light and viewer
    // directions; it lines up with the normal exactly in the mirror setup.
    const vec3<T> half = unit(to_light) + unit(to_viewer);
    const T c = cosine(normal, half);  // NaN when half = 0 (light and viewer opposite)
    if (!(c > T(0))) return T(0);
    return std::pow(std::min(c, T(1)), shininess);
}

template <class T>
vec3<T> shadow_ray_origin(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_light) {
    if (!usable_direction(normal)) throw std::invalid_argument("shadow_ray_origin: the normal must be non-zero and finite");
    if (!is_finite(to_light)) throw std::invalid_argument("shadow_ray_origin: to_light must be finite");
    // Rounding errors in the hit point are a few units in the last place of
    // its largest coordinate (or of 1, for points near the origin): step
    // well clear of them, on the side the light is.
    const T magnitude = std::max({T(1), std::fabs(point.x), std::fabs(point.y), std::fabs(point.z)});
    const T offset = shadow_offset_epsilons<T> * std::numeric_limits<T>::epsilon() * magnitude;
    const T side = dot(normal, to_light) >= T(0) ? T(1) : T(-1);
    return point + (side * offset) * unit(normal);
}

template <class T>
shadow_query<T> shadow_ray(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& light_position) {
    shadow_query<T> q;
    q.r.origin = shadow_ray_origin(point, normal, light_position - point);
    const vec3<T> to_light = light_position - q.r.origin;
    const T distance = length(to_light);
    if (!(distance > T(0))) {
        q.r.direction = vec3<T>(0);
        q.range = {T(0), T(0)};  // empty: nothing can block a light that sits on the origin
        return q;
    }
    // A unit direction makes t a distance, so "between the point and the
    // light" is simply 0 < t < distance: blockers beyond the light do not count.
    q.r.direction = to_light / distance;
    q.range = {T(0), distance};
    return q;
}

template <class T>
color shade(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_viewer, const material& m,
            const std::vector<point_light>& lights, const color& ambient, const occlusion_test<T>& occluded) {
    if (!usable_direction(normal)) throw std::invalid_argument("shade: the normal must be non-zero and finite");
    if (!usable_direction(to_viewer)) throw std::invalid_argument("shade: to_viewer must be non-zero and finite");
    if (!(m.shininess >= 0.0f)) throw std::invalid_argument("shade: the material's shininess must be >= 0");

    color result = ambient * m.diffuse;
    for (const point_light& light : lights) {
        const vec3<T> light_position = convert<T>(light.position);
        const vec3<T> to_light = light_position - point;
        const T cos_term = lambert(normal, to_light);
        if (!(cos_term > T(0))) continue;  // below the surface (or at the point): no light, no shadow ray
        const shadow_query<T> q = shadow_ray(point, normal, light_position);
        if (occluded(q.r, q.range)) continue;
        // Inverse-square law: the light's power spreads over a sphere of area 4 pi d^2.
        const T d2 = dot(to_light, to_light);
        const float falloff = float(T(1) / d2);
        const float highlight = float(blinn_phong(normal, to_light, to_viewer, T(m.shininess)));
        result += light.intensity * falloff * (m.diffuse * float(cos_term) + m.specular * highlight);
    }
    return result;
}

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
