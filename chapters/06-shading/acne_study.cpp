// acne_study.cpp — how big must the shadow-ray offset be? A measurement,
// not an exercise: it prints the table in README.md, "Shadow acne".
//
// For each test sphere, a grid of camera rays hits the sphere (chapter 02's
// intersect_sphere); every hit the light can see sends its shadow ray back
// at the same sphere. A convex sphere can never truly shadow its own lit
// side, so every such hit is shadow acne. The origin is moved along the
// normal either by the course's rule with k epsilons in place of
// shadow_offset_epsilons (your shadow_ray_origin's step, scaled by
// k / shadow_offset_epsilons) or by a fixed distance (the tempting shortcut).
//
//   ch06-acne-study            prints one line per sphere, precision and offset
#include "02-sphere/sphere.hpp"
#include "06-shading/shading.hpp"

#include "common/stub.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace {

using namespace rt;

// How a shadow ray's origin is pushed off the surface.
template <class T>
struct offset_rule {
    bool scaled = true;  // true: k * epsilon * M; false: a fixed distance
    T amount = 0;        // k, or the fixed distance

    vec3<T> apply(const vec3<T>& p, const vec3<T>& unit_normal) const {
        if (!scaled) return p + amount * unit_normal;
        // Your chapter 06 shadow_ray_origin steps shadow_offset_epsilons<T> epsilons (of the point's
        // scale) towards the light, here on the normal's side; k epsilons is that step times k / 128.
        const vec3<T> step = ch06::shadow_ray_origin(p, unit_normal, unit_normal) - p;
        return p + (amount / ch06::shadow_offset_epsilons<T>) * step;
    }
};

// Fraction of lit hits whose shadow ray hits their own sphere.
template <class T>
double acne_fraction(const sphere<T>& s, const vec3<T>& eye, const vec3<T>& light, const offset_rule<T>& rule) {
    const int n = 200;
    long lit = 0, acne = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const T u = (T(i) + T(0.5)) / T(n) * T(2) - T(1);
            const T v = (T(j) + T(0.5)) / T(n) * T(2) - T(1);
            const vec3<T> aim = s.center + s.radius * vec3<T>(u, v, T(0));
            auto hit = ch02::intersect_sphere(s, ray<T>{eye, aim - eye}, interval<T>{T(0), infinity<T>});
            if (!hit || !(dot(hit->normal, light - hit->point) > T(0))) continue;
            ++lit;
            const vec3<T> origin = rule.apply(hit->point, hit->normal);
            const vec3<T> to_light = light - origin;
            const T distance = length(to_light);
            if (ch02::intersect_sphere(s, ray<T>{origin, to_light / distance}, interval<T>{T(0), distance})) ++acne;
        }
    return lit ? double(acne) / double(lit) : std::nan("");  // NaN: nothing was lit
}

template <class T>
void study(const char* name, const sphere<T>& s, const vec3<T>& eye, const vec3<T>& light) {
    const char* precision = sizeof(T) == 4 ? "float " : "double";
    std::printf("%-22s %s  scaled k:", name, precision);
    for (T k : {T(0), T(1), T(2), T(4), T(8), T(128)})
        std::printf("  %g: %5.1f%%", double(k), 100 * acne_fraction(s, eye, light, offset_rule<T>{true, k}));
    std::printf("   fixed:");
    for (T fixed : {T(1e-6), T(1e-4), T(1e-2)})
        std::printf("  %g: %5.1f%%", double(fixed), 100 * acne_fraction(s, eye, light, offset_rule<T>{false, fixed}));
    std::printf("\n");
}

template <class T>
void study_all() {
    study<T>("unit sphere, 3 away", {{0, 0, -3}, T(1), 0}, vec3<T>(0), vec3<T>(4, 5, 2));
    study<T>("radius 1e4, 1e5 away", {{0, 0, T(-1e5)}, T(1e4), 0}, vec3<T>(0),
             vec3<T>(T(1e5), T(1e5), T(-5e4)));
    // Double only: in float this sphere is not even hit, because b^2 in the
    // quadratic (about 1e56) overflows float's range (chapter 07).
    if (sizeof(T) == sizeof(double))
        study<T>("radius 1e13, 1e14 away", {{0, 0, T(-1e14)}, T(1e13), 0}, vec3<T>(0),
                 vec3<T>(T(1e14), T(1e14), T(-5e13)));
}

}  // namespace

int main() {
    try {
        std::printf("shadow acne: share of lit hits whose shadow ray hits their own sphere (200 x 200 rays)\n");
        study_all<float>();
        study_all<double>();
        return 0;
    } catch (const rt::not_implemented& e) {
        std::fprintf(stderr, "ch06-acne-study: %s\n", e.what());
        return rt::exit_not_implemented;
    }
}
