// path_tracing.hpp — chapter 12's exercise: light that bounces.
//
// Four functions, each testable on its own; the last puts them together.
// Your code goes in path_tracing.cpp; the reference solution implements
// exactly these declarations. README.md is the lecture behind them.
//
// Every function takes its random numbers as arguments (u, u1, u2 in [0, 1)),
// so a call is a pure function: the same numbers give the same answer, bit
// for bit. The chapter's program draws them from a seeded generator per pixel.
//
// Words used below:
//   normal     a unit surface normal, on the side the light arrives from
//   direction  a unit vector leaving the surface
//   albedo     a Lambertian surface's reflectance (colour, each channel in [0, 1]);
//              its BRDF is albedo / pi, the same for every pair of directions
//   pdf        a density per steradian: how likely a direction is to be drawn
#pragma once

#include "path_scene.hpp"
#include "sphere_light.hpp"

#include <vector>

namespace rt::ch12 {

// A direction drawn on the hemisphere, with its density.
template <class T>
struct direction_sample {
    vec3<T> direction{0, 0, 0};  // unit, dot(normal, direction) >= 0
    T pdf = 0;                   // per steradian, at `direction`
};

// cosine_hemisphere_pdf — the density of cosine-weighted sampling:
//     pdf(direction) = max(0, dot(normal, direction)) / pi
// It integrates to 1 over the hemisphere (the integral of cos(theta) over it is pi).
// A direction below the surface (dot <= 0) has density 0. Never NaN for unit inputs.
template <class T>
T cosine_hemisphere_pdf(const vec3<T>& normal, const vec3<T>& direction);

// cosine_hemisphere — a direction drawn with density cos(theta) / pi.
//
// Malley's method: a point drawn uniformly on the unit disc, lifted straight
// up onto the hemisphere. With r = sqrt(u1) and phi = 2 pi u2, the local
// direction is (r cos phi, r sin phi, sqrt(1 - u1)) in tangent_frame(normal)
// (path_scene.hpp: x along t, y along b, z along the normal). Returns it with
// pdf = cosine_hemisphere_pdf(normal, direction) computed from its z, i.e.
// sqrt(1 - u1) / pi.
//   * u1 = 0 gives the normal itself; u1 near 1 grazes the surface, and its
//     pdf goes to 0 but never below, and is never NaN.
template <class T>
direction_sample<T> cosine_hemisphere(const vec3<T>& normal, T u1, T u2);

// light_contribution — what one light sample adds at a diffuse point
// (next-event estimation's estimate of the direct light):
//     albedo / pi * l.radiance * cos(theta) / l.pdf,   cos(theta) = dot(normal, l.direction)
// The caller has already checked that nothing blocks the light.
//   * The light below the surface (cos <= 0): black.
//   * No sample (l.pdf <= 0, or a pdf or direction that is not finite): black, never inf or NaN.
template <class T>
color light_contribution(const color& albedo, const vec3<T>& normal, const light_sample<T>& l);

// roulette_weight — Russian roulette on a path whose throughput is `throughput`.
//
// The path survives with probability p = min(1, the largest channel of
// throughput): it survives when u < p, and then its weight is 1 / p (so the
// expected weight is p * (1/p) = 1: roulette adds noise, never bias). A path
// that does not survive gets weight 0 and ends.
//   * A black (or negative, or NaN) throughput: p = 0, weight 0 (nothing left to carry).
//   * A throughput at or above 1 in some channel: p = 1, weight exactly 1.
template <class T>
T roulette_weight(const color& throughput, T u);

// The random numbers one bounce of a path uses, each in [0, 1).
template <class T>
struct bounce_numbers {
    T light_u1 = 0, light_u2 = 0;  // the light sample (next-event estimation)
    T bounce_u1 = 0, bounce_u2 = 0;  // the direction of the next bounce
    T roulette_u = 0;              // Russian roulette
};

// Which estimator path_radiance evaluates (the lecture compares all four).
struct path_settings {
    bool next_event = true;       // sample the lights at every matte vertex
    bool cosine_sampling = true;  // bounce by cosine_hemisphere (else uniform_hemisphere)
    int roulette_after = 3;       // bounces before roulette starts (a huge number: never)
};

// path_radiance — the radiance arriving along camera_ray: the path loop.
//
// Vertex k (k = 0, 1, ...) uses numbers[k]; the path has at most
// numbers.size() vertices. With throughput beta = 1 and sum L = 0 at first,
// at each vertex:
//   1. hit = closest_surface(s, r, range); a miss adds beta * s.background and ends
//      the path. range is camera_range for the camera ray, (0, infinity) after.
//   2. The hit surface's emission is added, beta * emission, unless next-event
//      estimation already counted it: with settings.next_event, a light of
//      s.lights reached by the bounce from a matte vertex adds nothing (its
//      light arrived through that vertex's light sample, step 5). The camera
//      ray's hit always counts, and so does a light reached by the ray that
//      leaves glass (step 3): no light sample saw the light along it.
//   3. Glass (hit.material.ior > 0) is a specular vertex: no light sample (a
//      sample's direction is never the one glass sends light along) and no
//      roulette; the next ray is glass_bounce(s, hit, r, bounce_u1)
//      (path_scene.hpp), beta unchanged, and the path goes on at step 1.
//   4. A black matte surface (albedo 0 in every channel) ends the path.
//   5. With settings.next_event: for every light i of s.lights, the sample
//      sample_light(s, i, p, light_u1, light_u2) from the point p moved off the
//      surface, p = ch06::shadow_ray_origin(hit point, normal, normal), adds
//      beta * light_contribution(albedo, normal, sample) when it has pdf > 0 and
//      light_visible(s, p, sample).
//   6. The next direction: cosine_hemisphere(normal, bounce_u1, bounce_u2) or,
//      without settings.cosine_sampling, uniform_hemisphere(...) with its pdf;
//      beta *= albedo / pi * cos(theta) / pdf.
//   7. From vertex k >= settings.roulette_after on, beta *= roulette_weight(beta,
//      roulette_u); a weight of 0 ends the path.
//   8. The next ray leaves from p in the new direction.
// Returns L. Never negative, never inf or NaN (a NaN throughput ends the path).
// Throws std::invalid_argument when a surface's albedo is above 1 or below 0,
// or an emission is negative or not finite (the loop would make energy).
template <class T>
color path_radiance(const path_scene<T>& s, const ray<T>& camera_ray, const interval<T>& camera_range,
                    const std::vector<bounce_numbers<T>>& numbers, const path_settings& settings);

}  // namespace rt::ch12
