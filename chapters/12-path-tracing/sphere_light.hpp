// sphere_light.hpp — a direction towards a sphere light, drawn by solid angle.
//
// Seen from a point outside it, a sphere of radius R at distance d fills a
// cone of half-angle theta_max, sin(theta_max) = R / d. Drawing the direction
// uniformly inside that cone has the density 1 / (2 pi (1 - cos theta_max))
// per steradian, and every direction drawn meets the sphere: no sample is
// wasted on a direction that misses the light (the lecture, "Next-event
// estimation"). Chapter 11's sample_sphere_light draws it (its exercise);
// this file turns its answer into what chapter 12's light sample needs.
#pragma once

#include "path_scene.hpp"

#include "11-sampling/sampling.hpp"

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
    light_sample<T> out;  // pdf 0: no sample, when the point is on or inside the light
    const std::optional<ch11::light_sample<T>> drawn = ch11::sample_sphere_light(light, point, ch11::vec2<T>(u1, u2));
    if (!drawn) return out;
    out.direction = drawn->direction;
    out.pdf = drawn->pdf;
    out.radiance = s.surfaces.at(size_t(light.material)).emission;
    out.object = index;
    return out;
}

}  // namespace rt::ch12
