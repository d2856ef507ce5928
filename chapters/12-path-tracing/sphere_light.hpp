// sphere_light.hpp — a direction towards a sphere light, drawn by solid angle.
//
// Seen from a point outside it, a sphere of radius R at distance d fills a
// cone of half-angle theta_max, sin(theta_max) = R / d. Drawing the direction
// uniformly inside that cone has the density 1 / (2 pi (1 - cos theta_max))
// per steradian, and every direction drawn meets the sphere: no sample is
// wasted on a direction that misses the light (the lecture, "Next-event
// estimation"). Chapter 11 derives this mapping; chapter 12 calls it.
#pragma once

#include "path_scene.hpp"

namespace rt::ch12 {

// One direction towards a light, what travels along it, and how likely it was.
template <class T>
struct light_sample {
    vec3<T> direction{0, 0, 0};  // unit, from the point towards the light
    T pdf = 0;                   // density of `direction` per steradian; 0 means "no sample"
    color radiance{0.0f};        // the light's emitted radiance along -direction
    int object = -1;             // the light's object number: the direction is unblocked when
                                 // the closest hit along it is this object
};

// A direction from `point` into the cone that sphere light `s` subtends, from
// u1, u2 in [0, 1). A point inside the sphere (or on it) gets no sample (pdf 0).
template <class T>
light_sample<T> sample_sphere_light(const sphere<T>& s, const color& radiance, int object, const vec3<T>& point,
                                    T u1, T u2) {
    light_sample<T> out;
    const vec3<T> to_center = s.center - point;
    const T d = length(to_center);
    if (!(d > s.radius)) return out;
    const T sin2_max = (s.radius / d) * (s.radius / d);
    const T cos_max = std::sqrt(std::max(T(0), T(1) - sin2_max));
    // 1 - cos(theta_max) written without the cancellation of two numbers near 1
    // (a small, far light: sin2_max = 1e-8 would leave 1 - cos_max = 0 in float).
    const T one_minus_cos_max = sin2_max / (T(1) + cos_max);
    const T one_minus_cos = u1 * one_minus_cos_max;  // cos(theta) uniform in [cos_max, 1]
    const T cos_theta = T(1) - one_minus_cos;
    const T sin_theta = std::sqrt(std::max(T(0), one_minus_cos * (T(2) - one_minus_cos)));
    const T phi = T(2) * pi<T> * u2;
    out.direction = normalize(tangent_frame<T>(to_center / d).to_world(sin_theta * std::cos(phi),
                                                                       sin_theta * std::sin(phi), cos_theta));
    out.pdf = T(1) / (T(2) * pi<T> * one_minus_cos_max);
    out.radiance = radiance;
    out.object = object;
    return out;
}

// Whether the light sample is seen from `origin` (a point already moved off
// its surface): the first thing a ray along the sample's direction meets is
// the light itself.
template <class T>
bool light_visible(const path_scene<T>& s, const vec3<T>& origin, const light_sample<T>& l) {
    const std::optional<surface_hit<T>> hit = closest_surface(s, ray<T>{origin, l.direction}, {T(0), infinity<T>});
    return hit && hit->hit.object == l.object;
}

// The sample of light number `k` of the scene (s.lights[k]) as seen from point.
template <class T>
light_sample<T> sample_light(const path_scene<T>& s, size_t k, const vec3<T>& point, T u1, T u2) {
    const int index = s.lights.at(k);
    const sphere<T>& light = s.geometry.spheres.at(size_t(index));
    return sample_sphere_light(light, s.surfaces.at(size_t(light.material)).emission, index, point, u1, u2);
}

}  // namespace rt::ch12
