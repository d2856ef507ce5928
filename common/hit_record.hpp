// hit_record.hpp — what an intersection routine reports about a hit, and
// the one rule for which side of the surface the ray is on.
//
// Every shape reports its OUTWARD normal: the geometry's own normal, the
// same whichever side the ray comes from (sphere: away from the centre;
// plane: its stored normal; triangle: (b - a) x (c - a), the side from which
// its corners run counter-clockwise). Which side the ray arrives on is then
// decided here, once, for every shape:
//
//   front_face     the ray arrives on the side the outward normal points
//                  to (dot(direction, outward) < 0);
//   facing_normal  the unit normal on the ray's side: the outward normal on
//                  a front face, its negative on a back face (a plane seen
//                  from below, the inside of a sphere).
//
// Shading lights the side the viewer sees, so it takes facing_normal(r).
// Chapter 09 needs the side itself: a refracted ray entering glass
// (front_face) bends by 1/eta, one leaving it by eta, and a secondary ray
// starts offset to the side it leaves by.
//
//   const rt::color c = ch06::shade(hit->point, hit->facing_normal(r), -r.direction, ...);
//   const T eta_ratio = hit->front_face(r) ? 1 / eta : eta;
//
// A ray that grazes the surface (dot exactly 0) counts as a back face; a
// shape never reports a hit there except tangent to a sphere, where either
// side is the same point.
#pragma once

#include "math.hpp"
#include "ray.hpp"

namespace rt {

// The rule, on vectors (for code that keeps hits in its own arrays, such as
// the renderer's packets). outward is a unit outward normal, direction the
// ray's direction (any length).
template <class T>
bool front_face(const vec3<T>& outward, const vec3<T>& direction) {
    return dot(direction, outward) < T(0);
}

template <class T>
vec3<T> facing_normal(const vec3<T>& outward, const vec3<T>& direction) {
    return front_face(outward, direction) ? outward : -outward;
}

template <class T>
struct hit_record {
    T t = 0;          // ray parameter of the hit: the point is ray.at(t)
    vec3<T> point{};  // the hit point
    vec3<T> normal{}; // the unit OUTWARD normal at the hit, whichever side the ray comes from
    int object = -1;  // index of the object hit in its scene, -1 when not from a scene

    // The rule above, for the ray r that made this hit.
    bool front_face(const ray<T>& r) const { return rt::front_face(normal, r.direction); }
    vec3<T> facing_normal(const ray<T>& r) const { return rt::facing_normal(normal, r.direction); }
};

}  // namespace rt
