// optics.hpp — chapter 09's first exercise: where light goes at a smooth
// surface, and how much of it.
//
// Four small functions: the mirror direction, the refracted direction (or
// none), and the share of light a glass surface reflects, exactly and by
// Schlick's approximation. Your code goes in optics.cpp; the reference
// solution implements exactly these declarations. README.md is the lecture.
//
// Words used below:
//   d        the incoming direction, pointing *at* the surface; any length > 0
//   n        a unit normal on the side d comes from: dot(d, n) < 0
//            (surface_hit::facing_normal() in whitted.hpp gives it)
//   eta      the ratio of refractive indices n_incident / n_transmitted, > 0:
//            1 / 1.5 for a ray entering glass from air, 1.5 for one leaving it
//   cos_i    cos(theta_i) = dot(-d / |d|, n), the cosine of the angle between
//            the incoming ray and the normal, in [0, 1]
#pragma once

#include "common/math.hpp"

#include <optional>

namespace rt::ch09 {

// reflect — the mirror direction of d about the surface with normal n.
//
// Returns  r = d - 2 dot(d, n) n.
//   * The angle of r to the normal equals that of d, r lies in the plane of
//     d and n, and |r| = |d| for any length of d (no normalising: a ray's
//     direction length is its convention for t, and this keeps it).
//   * n must be unit length (the formula assumes it); d need not be.
//   * d on either side of the surface: the formula is the same, so the sign
//     of n does not matter (reflecting about -n gives the same r).
template <class T>
vec3<T> reflect(const vec3<T>& d, const vec3<T>& n);

// refract — the direction of the ray transmitted through the surface
// (Snell's law, n_i sin(theta_i) = n_t sin(theta_t), in vector form).
//
// Inputs   d (any length > 0), n (unit, facing d: dot(d, n) < 0), eta > 0.
// Returns  the unit transmitted direction
//              t = eta u + (eta cos_i - cos_t) n,   u = d / |d|,
//          cos_i = -dot(u, n),  cos_t = sqrt(1 - eta^2 (1 - cos_i^2)),
//          which goes through the surface: dot(t, n) = -cos_t <= 0.
//   * Total internal reflection: when eta^2 (1 - cos_i^2) > 1 (only possible
//     for eta > 1, past the critical angle sin(theta_c) = 1 / eta) there is
//     no transmitted ray: returns std::nullopt.
//   * Exactly at the critical angle (eta^2 (1 - cos_i^2) == 1 as computed)
//     the transmitted ray grazes the surface: t is perpendicular to n.
//   * At normal incidence (u = -n) t = u: the ray goes straight through.
//   * Never returns NaN for inputs that keep these rules.
template <class T>
std::optional<vec3<T>> refract(const vec3<T>& d, const vec3<T>& n, T eta);

// fresnel_dielectric — the fraction of unpolarised light a smooth surface
// between two transparent media reflects (Fresnel's equations, exact).
//
// Inputs   cos_i in [0, 1] (the incident side's cosine), eta = n_i / n_t > 0.
// Returns  R = (r_s^2 + r_p^2) / 2 with
//              r_s = (eta cos_i - cos_t) / (eta cos_i + cos_t)
//              r_p = (cos_i - eta cos_t) / (cos_i + eta cos_t)
//          and cos_t as in refract. The transmitted fraction is 1 - R.
//   * Total internal reflection (eta^2 (1 - cos_i^2) >= 1): returns 1.
//   * Normal incidence (cos_i = 1): R = ((1 - eta) / (1 + eta))^2, which is
//     ((n1 - n2) / (n1 + n2))^2: 0.04 for air and glass of index 1.5.
//   * Grazing incidence (cos_i = 0): R = 1.
//   * In [0, 1], never NaN. cos_i outside [0, 1] is clamped into it.
template <class T>
T fresnel_dielectric(T cos_i, T eta);

// schlick — Schlick's approximation of fresnel_dielectric.
//
// Returns  R0 + (1 - R0) (1 - c)^5,   R0 = ((1 - eta) / (1 + eta))^2,
// where c is the cosine on the side of the *lower* index: c = cos_i when
// eta <= 1 (light arriving from the less dense medium), and c = cos_t when
// eta > 1 (light inside glass; Schlick's fit is for that angle). Inside glass
// past the critical angle: returns 1, like fresnel_dielectric.
//   * Equal to fresnel_dielectric at normal incidence and at grazing
//     incidence; in between it is off by up to a few percent of R0's size
//     (README, "What Schlick costs", measures by how much).
//   * In [0, 1], never NaN. cos_i outside [0, 1] is clamped into it.
template <class T>
T schlick(T cos_i, T eta);

}  // namespace rt::ch09
