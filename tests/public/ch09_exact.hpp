// ch09_exact.hpp — which side of a surface a point is on, decided exactly
// enough to call a self-intersection a self-intersection (chapter 09's tests).
//
// A secondary ray re-hits the surface it leaves exactly when its origin lies
// on the wrong side of the *exact* surface (the shape as stored in T): a
// reflected ray that starts inside a sphere meets the sphere again, a
// refracted one that starts outside never gets in. So these tests do not ask
// an intersection routine (its own rounding would blur the answer); they
// evaluate the side in __float128 (113-bit significand), where the products
// of the T inputs are exact and the sums err by far less than the margins
// tested. Positive: outside (the side the outward normal points to).
#pragma once

#include "common/math.hpp"
#include "common/shapes.hpp"

namespace rt::test {

__extension__ typedef __float128 quad;

template <class T>
quad quad_dot(const vec3<T>& a, const vec3<T>& b) {
    return quad(a.x) * quad(b.x) + quad(a.y) * quad(b.y) + quad(a.z) * quad(b.z);
}

// Sign of |p - c|^2 - r^2: > 0 outside the sphere, < 0 inside.
template <class T>
int sphere_side(const sphere<T>& s, const vec3<T>& p) {
    const quad dx = quad(p.x) - quad(s.center.x), dy = quad(p.y) - quad(s.center.y), dz = quad(p.z) - quad(s.center.z);
    const quad value = dx * dx + dy * dy + dz * dz - quad(s.radius) * quad(s.radius);
    return value > 0 ? 1 : value < 0 ? -1 : 0;
}

// Sign of (p - q) . m: > 0 on the side the plane's normal points to.
template <class T>
int plane_side(const plane<T>& pl, const vec3<T>& p) {
    const quad value = (quad(p.x) - quad(pl.point.x)) * quad(pl.normal.x) +
                       (quad(p.y) - quad(pl.point.y)) * quad(pl.normal.y) +
                       (quad(p.z) - quad(pl.point.z)) * quad(pl.normal.z);
    return value > 0 ? 1 : value < 0 ? -1 : 0;
}

// Sign of det(b - a, c - a, p - a): > 0 on the side (b - a) x (c - a) points to.
template <class T>
int triangle_side(const triangle<T>& tr, const vec3<T>& p) {
    const quad e1[3] = {quad(tr.b.x) - quad(tr.a.x), quad(tr.b.y) - quad(tr.a.y), quad(tr.b.z) - quad(tr.a.z)};
    const quad e2[3] = {quad(tr.c.x) - quad(tr.a.x), quad(tr.c.y) - quad(tr.a.y), quad(tr.c.z) - quad(tr.a.z)};
    const quad f[3] = {quad(p.x) - quad(tr.a.x), quad(p.y) - quad(tr.a.y), quad(p.z) - quad(tr.a.z)};
    const quad m[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const quad value = m[0] * f[0] + m[1] * f[1] + m[2] * f[2];
    return value > 0 ? 1 : value < 0 ? -1 : 0;
}

}  // namespace rt::test
