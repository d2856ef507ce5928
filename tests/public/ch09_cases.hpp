// ch09_cases.hpp — stiff surface points for chapter 09's spawn tests.
//
// Each family is a shape where rounding hurts: a ground sphere of radius
// 1e6 (its hit points carry the rounding of numbers near 1e6), a unit sphere
// thousands of units away, a sphere of radius 1e-4, triangles a million units
// across and a ten-thousandth of a unit across, a tilted plane seen out to
// 1e4, and rays that graze. A case holds a surface point (put back on the
// surface with its bound, surface_error.hpp), the outward normal, a
// direction arriving from outside, and the exact side test of its shape.
#pragma once

#include "ch09_exact.hpp"

#include "09-reflection/surface_error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace rt::test {

template <class T>
struct spawn_case {
    std::string family;
    ch09::surface_point<T> surface;
    vec3<T> outward;   // unit normal on the outside
    vec3<T> incoming;  // arrives from outside: dot(incoming, outward) < 0
    std::function<int(const vec3<T>&)> side;  // exact: > 0 outside, < 0 inside, 0 on the surface
    T size = 1;        // the object's size (radius, longest edge; 1 for a plane): what a "thin" shell is measured by
};

namespace cases_detail {

template <class T>
struct rng {
    std::mt19937_64 gen;
    explicit rng(unsigned long long seed) : gen(seed) {}
    T uniform(T lo, T hi) { return T(std::uniform_real_distribution<double>(double(lo), double(hi))(gen)); }
    vec3<T> unit() {
        for (;;) {
            const vec3<T> v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            const T len2 = dot(v, v);
            if (len2 > T(0.01) && len2 < T(1)) return v / std::sqrt(len2);
        }
    }
};

// A direction arriving at a surface with unit normal n: from the eye when
// grazing is 0, otherwise nearly along the surface (its normal part a
// `grazing` fraction of its length).
template <class T>
vec3<T> arriving(rng<T>& g, const vec3<T>& n, const vec3<T>& from_eye, T grazing) {
    if (grazing == T(0)) return from_eye;
    vec3<T> tangent = cross(n, g.unit());
    tangent = tangent / length(tangent);
    return tangent - grazing * n;
}

template <class T>
void add_sphere_cases(std::vector<spawn_case<T>>& out, const std::string& family, const sphere<T>& s,
                      const vec3<T>& eye, T cap, T grazing, int count, rng<T>& g) {
    // Points on the part of the sphere facing the eye, within `cap` (radians-ish) of its middle.
    const vec3<T> towards_eye = (eye - s.center) / length(eye - s.center);
    for (int i = 0; i < count; ++i) {
        vec3<T> u = towards_eye + cap * g.unit();
        u = u / length(u);
        const vec3<T> p = s.center + s.radius * u;
        spawn_case<T> c;
        c.family = family;
        c.surface = ch09::on_sphere(s, p);
        c.outward = (c.surface.point - s.center) / s.radius;
        c.outward = c.outward / length(c.outward);
        c.incoming = arriving(g, c.outward, c.surface.point - eye, grazing);
        if (!(dot(c.incoming, c.outward) < T(0))) continue;
        c.side = [s](const vec3<T>& o) { return sphere_side(s, o); };
        c.size = s.radius;
        out.push_back(c);
    }
}

template <class T>
void add_triangle_cases(std::vector<spawn_case<T>>& out, const std::string& family, const triangle<T>& tr,
                        const vec3<T>& eye, T grazing, int count, rng<T>& g) {
    vec3<T> n = cross(tr.b - tr.a, tr.c - tr.a);
    n = n / length(n);
    for (int i = 0; i < count; ++i) {
        T b1 = g.uniform(0, 1), b2 = g.uniform(0, 1);
        if (b1 + b2 > T(1)) b1 = T(1) - b1, b2 = T(1) - b2;
        const vec3<T> p = tr.a + b1 * (tr.b - tr.a) + b2 * (tr.c - tr.a);
        spawn_case<T> c;
        c.family = family;
        c.surface = ch09::on_triangle(tr, p);
        c.outward = dot(eye - p, n) > T(0) ? n : -n;  // the side the eye is on counts as outside
        const triangle<T> facing = dot(eye - p, n) > T(0) ? tr : triangle<T>{tr.a, tr.c, tr.b, 0};
        c.incoming = arriving(g, c.outward, c.surface.point - eye, grazing);
        if (!(dot(c.incoming, c.outward) < T(0))) continue;
        c.side = [facing](const vec3<T>& o) { return triangle_side(facing, o); };
        c.size = std::max({length(tr.b - tr.a), length(tr.c - tr.a), length(tr.c - tr.b)});
        out.push_back(c);
    }
}

template <class T>
void add_plane_cases(std::vector<spawn_case<T>>& out, const std::string& family, const plane<T>& pl, T extent,
                     T grazing, int count, rng<T>& g) {
    const vec3<T> n = pl.normal / length(pl.normal);
    const vec3<T> u = normalize(cross(n, vec3<T>(T(0.3), T(0.9), T(-0.2))));
    const vec3<T> v = cross(n, u);
    for (int i = 0; i < count; ++i) {
        const vec3<T> p = pl.point + g.uniform(-extent, extent) * u + g.uniform(-extent, extent) * v;
        const vec3<T> eye = pl.point + T(3) * n + g.uniform(-1, 1) * u;
        spawn_case<T> c;
        c.family = family;
        c.surface = ch09::on_plane(pl, p);
        c.outward = n;
        c.incoming = arriving(g, n, c.surface.point - eye, grazing);
        if (!(dot(c.incoming, c.outward) < T(0))) continue;
        c.side = [pl](const vec3<T>& o) { return plane_side(pl, o); };
        out.push_back(c);
    }
}

}  // namespace cases_detail

// The stiff families, `count` points each (a few fewer where a random
// direction would not arrive from outside), drawn from `seed`.
template <class T>
std::vector<spawn_case<T>> stiff_spawn_cases(unsigned long long seed, int count) {
    using namespace cases_detail;
    rng<T> g(seed);
    std::vector<spawn_case<T>> out;
    const vec3<T> eye(0, 2, 0);
    add_sphere_cases(out, "ground sphere of radius 1e6", sphere<T>{{0, T(-1e6), 0}, T(1e6), 0}, eye, T(1e-3), T(0),
                     count, g);
    add_sphere_cases(out, "unit sphere 4100 units away", sphere<T>{{T(2900), T(150), T(-2900)}, 1, 0}, vec3<T>(0),
                     T(0.9), T(0), count, g);
    add_sphere_cases(out, "sphere of radius 1e-4", sphere<T>{{T(1e-3), T(2e-3), T(-5e-3)}, T(1e-4), 0}, vec3<T>(0),
                     T(0.9), T(0), count, g);
    add_sphere_cases(out, "grazing rays on a unit sphere", sphere<T>{{1, 2, -3}, 1, 0}, vec3<T>(0), T(0.9), T(1e-4),
                     count, g);
    add_triangle_cases(out, "triangle a million units across",
                       triangle<T>{{T(-1e6), T(-1), T(-1e6)}, {T(1e6), T(0.5), T(-1e6)}, {0, T(2), T(1e6)}, 0}, eye,
                       T(0), count, g);
    add_triangle_cases(out, "triangle 1e-4 across, far out",
                       triangle<T>{{T(100), T(50), T(-200)}, {T(100.0001), T(50), T(-200)}, {T(100), T(50.0001), T(-200.00003)}, 0},
                       vec3<T>(0), T(0), count, g);
    add_triangle_cases(out, "grazing rays on a triangle", triangle<T>{{-5, 0, -5}, {5, T(0.1), -5}, {0, T(-0.1), 5}, 0},
                       eye, T(1e-4), count, g);
    add_plane_cases(out, "tilted plane out to 1e4", plane<T>{{T(3.7), T(-1.2), T(5.1)}, {1, 2, 3}, 0}, T(1e4), T(0),
                    count, g);
    add_plane_cases(out, "grazing rays on a tilted plane", plane<T>{{T(3.7), T(-1.2), T(5.1)}, {1, 2, 3}, 0}, T(100),
                    T(1e-4), count, g);
    return out;
}

// The bound projected on the normal, dot(|n|, error): how far along n the
// exact surface may be from the computed point.
template <class T>
T reach_along(const ch09::surface_point<T>& p, const vec3<T>& n) {
    return dot(glm::abs(n), p.error);
}

// One float step of each component of p, along n: what the final rounding
// may add to the offset.
template <class T>
T float_steps_along(const vec3<T>& p, const vec3<T>& n) {
    T sum = 0;
    for (int i = 0; i < 3; ++i) {
        const T a = std::fabs(p[i]);
        sum += (std::nextafter(a, infinity<T>) - a) * std::fabs(n[i]);
    }
    return sum;
}

}  // namespace rt::test
