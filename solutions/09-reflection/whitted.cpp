// whitted.cpp — reference solution for chapter 09's recursive trace.
#include "09-reflection/whitted.hpp"

#include <algorithm>
#include <stdexcept>

namespace rt::ch09 {

namespace {

float largest(const color& c) {
    return std::max({c.r, c.g, c.b});
}

// The colour a secondary ray s adds, scaled by its weight w, or nothing when
// it could not change the picture (its throughput is below the cut-off).
template <class T>
color secondary(const scene<T>& world, const ray<T>& s, const color& w, int depth, float throughput) {
    const float next = throughput * largest(w);
    if (!(next >= min_throughput)) return color(0.0f);
    return w * trace(world, s, interval<T>{T(0), infinity<T>}, depth - 1, next);
}

}  // namespace

template <class T>
color trace(const scene<T>& world, const ray<T>& r, const interval<T>& range, int depth, float throughput) {
    if (depth < 0) throw std::invalid_argument("trace: depth must be >= 0");
    const std::optional<surface_hit<T>> h = closest_surface_hit(world, r, range);
    if (!h) return world.background;
    color c = local_light(world, *h, r);
    if (depth == 0) return c;  // no more bounces: the local light is all

    const vec3<T> n = h->facing_normal();
    const material& m = h->m;
    if (largest(m.mirror) > 0.0f)
        c += secondary(world, spawn_ray(h->surface, n, reflect(r.direction, n)), m.mirror, depth, throughput);
    if (m.ior > 0.0f) {
        // Entering, light goes from air (1) into the glass (ior); leaving, the reverse.
        const T eta = h->front_face ? T(1) / T(m.ior) : T(m.ior);
        const T cos_i = -dot(r.direction, n) / length(r.direction);
        const T f = fresnel_dielectric(cos_i, eta);
        c += secondary(world, spawn_ray(h->surface, n, reflect(r.direction, n)), color(float(f)), depth, throughput);
        if (const std::optional<vec3<T>> t = refract(r.direction, n, eta))
            c += secondary(world, spawn_ray(h->surface, n, *t), color(float(T(1) - f)), depth, throughput);
    }
    return c;
}

template color trace(const scene<float>&, const ray<float>&, const interval<float>&, int, float);
template color trace(const scene<double>&, const ray<double>&, const interval<double>&, int, float);

}  // namespace rt::ch09
