// shading.hpp — chapter 06's exercise: what colour is the point a ray hit?
//
// Five small functions, each testable on its own, then one that puts them
// together. Your code goes in shading.cpp; the reference solution implements
// exactly these declarations. README.md is the lecture behind them.
//
// Words used below:
//   point     a hit point on a surface (from chapters 02, 04, 05)
//   normal    the surface normal there, on the side being lit; any length
//             > 0 unless said otherwise. For a hit, the caller passes
//             hit.facing_normal(r), the normal on the viewer's side
//             (common/hit_record.hpp: one rule for every shape), so these
//             functions never turn it round themselves
//   to_light  a vector from the point towards a light (any length > 0)
//   to_viewer a vector from the point back towards the eye (any length > 0),
//             e.g. minus the primary ray's direction
//   "below the surface"  on the other side of the surface from the normal:
//             dot(normal, to_light) <= 0
// Colours are linear RGB floats (common/math.hpp); geometry is in T.
#pragma once

#include "common/interval.hpp"
#include "common/math.hpp"
#include "common/ray.hpp"
#include "common/scene.hpp"

#include <functional>
#include <vector>

namespace rt::ch06 {

// lambert — Lambert's cosine law.
//
// Returns  max(0, cos(theta)) = max(0, dot(n, l) / (|n| |l|)), the fraction of
// a light's power per unit area that a surface facing `normal` receives from
// direction `to_light`. Neither vector needs to be unit length: the answer
// depends only on the angle between them, so it is in [0, 1].
//   * Light below the surface (cos <= 0): 0, never negative (a light cannot
//     take energy away).
//   * A zero-length or non-finite input: 0 (no NaN is ever returned).
template <class T>
T lambert(const vec3<T>& normal, const vec3<T>& to_light);

// blinn_phong — the strength of the Blinn-Phong highlight.
//
// With the half vector  h = l/|l| + v/|v|  (the direction halfway between
// the light and the viewer), returns  max(0, dot(n, h) / (|n| |h|))^shininess,
// a number in [0, 1] that is 1 exactly when the viewer sits in the mirror
// direction of the light about the normal.
//   * Light below the surface (dot(normal, to_light) <= 0): 0 (a light the
//     surface cannot see makes no highlight on it).
//   * Light and viewer exactly opposite (h = 0), or a zero-length or
//     non-finite input: 0, never NaN.
//   * shininess >= 0 (larger: smaller, sharper highlight). A negative or NaN
//     shininess is a bad material: throws std::invalid_argument.
template <class T>
T blinn_phong(const vec3<T>& normal, const vec3<T>& to_light, const vec3<T>& to_viewer, T shininess);

// How far shadow_ray_origin moves a point, in units of T's machine epsilon
// times the point's magnitude (README, "shadow acne").
template <class T>
inline constexpr T shadow_offset_epsilons = T(128);

// shadow_ray_origin — where a shadow ray starts, so it cannot hit the
// surface it leaves (shadow acne).
//
// The computed hit point is only known to within rounding: it may lie a
// little *below* the surface, and a shadow ray starting there hits its own
// surface. So the origin is pushed off the surface along the normal:
//     origin = point + s * offset * normal / |normal|
// where
//     s      = +1 if dot(normal, to_light) >= 0, else -1   (the light's side)
//     offset = shadow_offset_epsilons<T> * epsilon(T) * M
//     M      = max(1, |point.x|, |point.y|, |point.z|)
// epsilon(T) is std::numeric_limits<T>::epsilon(). The offset grows with the
// point's coordinates because rounding errors do (one unit in the last place
// of 1e5 is 0.0078 in float); it never drops below 128 epsilons of 1 because
// a point near the world origin still carries the errors of the larger
// numbers it was computed from (the eye, the ray's length).
//   * normal must be non-zero and finite, to_light finite; otherwise throws
//     std::invalid_argument (a shadow ray from a made-up origin would be a
//     silently wrong picture).
template <class T>
vec3<T> shadow_ray_origin(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_light);

// A shadow ray and the part of it that must be free of blockers.
template <class T>
struct shadow_query {
    ray<T> r;          // origin: shadow_ray_origin(...); direction: unit, towards the light
    interval<T> range; // (0, distance from r.origin to the light): only what lies between
                       // the point and the light can block it
};

// shadow_ray — the ray a point sends to ask "can I see this light?".
//
// Inputs   point, normal as above; light_position, the light's position.
// Returns  the query: r.origin = shadow_ray_origin(point, normal, light_position - point),
//          r.direction = the unit vector from r.origin to the light, and
//          range = (0, |light_position - r.origin|), so t measures distance and
//          anything at or beyond the light (t >= the light's distance) does not
//          count as a blocker.
//   * If the light sits exactly on the origin (distance 0), direction is
//     (0,0,0) and range is (0, 0): nothing can block it, and no NaN appears.
//   * Throws std::invalid_argument like shadow_ray_origin for a bad normal.
template <class T>
shadow_query<T> shadow_ray(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& light_position);

// How shade() asks the scene whether something blocks a shadow ray: true when
// any object is hit at a t inside range (tmin < t < tmax). The scene, and how
// it is intersected, stay the caller's business (chapter 03's loop, a BVH...).
template <class T>
using occlusion_test = std::function<bool(const ray<T>& r, const interval<T>& range)>;

// shade — the colour of a hit point: ambient plus, for every light the point
// can see, Lambert diffuse plus a Blinn-Phong highlight, falling off with the
// square of the distance.
//
// Inputs
//   point, normal  the hit point and its normal (any length > 0), on the side
//                  to light: the caller's hit.facing_normal(r), so the
//                  viewer sees that side. Used as given, never flipped (the
//                  face rule has already chosen the side, once).
//   to_viewer      towards the eye, any length > 0
//   m              the surface's material at this point: m.diffuse is the
//                  diffuse colour there (a checker pattern already resolved,
//                  rt::material_at in common/scene.hpp), m.specular and m.shininess the highlight
//   lights         point lights; light.intensity is the colour it delivers at
//                  distance 1, so at distance d it delivers intensity / d^2
//   ambient        light arriving from everywhere, unshadowed
//   occluded       the scene's blocker test (see occlusion_test)
//
// Returns, per colour channel,
//     ambient * m.diffuse
//   + sum over lights L that are above the surface, not at the point, and
//     not blocked (occluded(shadow_ray(point, n, L.position)) is false):
//         L.intensity / d^2 * ( m.diffuse  * lambert(n, l)
//                             + m.specular * blinn_phong(n, l, to_viewer, m.shininess) )
//   with l = L.position - point, d = |l| and n the normal as given.
//   * A light below the surface contributes nothing and costs no shadow ray.
//   * A light at distance 0 from the point contributes nothing (no infinity).
//   * Never negative, never NaN. Not clamped to 1: the image writer does that.
//   * Throws std::invalid_argument for a zero or non-finite normal or
//     to_viewer, or a bad shininess.
template <class T>
color shade(const vec3<T>& point, const vec3<T>& normal, const vec3<T>& to_viewer, const material& m,
            const std::vector<point_light>& lights, const color& ambient, const occlusion_test<T>& occluded);

}  // namespace rt::ch06
