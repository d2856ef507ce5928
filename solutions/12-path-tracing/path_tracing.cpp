// path_tracing.cpp — reference solution of chapter 12 (path_tracing.hpp holds the contracts).
#include "path_tracing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rt::ch12 {

template <class T>
T cosine_hemisphere_pdf(const vec3<T>& normal, const vec3<T>& direction) {
    const T cos_theta = dot(normal, direction);
    return cos_theta > T(0) ? cos_theta / pi<T> : T(0);  // NaN fails the test and gives 0
}

template <class T>
direction_sample<T> cosine_hemisphere(const vec3<T>& normal, T u1, T u2) {
    // A uniform point on the unit disc (area density 1/pi), lifted onto the
    // hemisphere: the lift multiplies the density by cos(theta).
    const T r = std::sqrt(u1);
    const T phi = T(2) * pi<T> * u2;
    const T z = std::sqrt(std::max(T(0), T(1) - u1));
    direction_sample<T> out;
    out.direction = tangent_frame<T>(normal).to_world(r * std::cos(phi), r * std::sin(phi), z);
    out.pdf = z / pi<T>;
    return out;
}

template <class T>
color light_contribution(const color& albedo, const vec3<T>& normal, const light_sample<T>& l) {
    if (!(l.pdf > T(0)) || !std::isfinite(l.pdf) || !is_finite(l.direction)) return color(0.0f);
    const T cos_theta = dot(normal, l.direction);
    if (!(cos_theta > T(0))) return color(0.0f);
    const float weight = float(cos_theta / (pi<T> * l.pdf));
    return albedo * l.radiance * weight;
}

template <class T>
T roulette_weight(const color& throughput, T u) {
    const float largest = std::max({throughput.r, throughput.g, throughput.b});
    if (!(largest > 0.0f)) return T(0);  // black, negative or NaN: nothing to carry
    if (largest >= 1.0f) return T(1);
    const T p = T(largest);
    return u < p ? T(1) / p : T(0);
}

namespace {

void check_surfaces(const std::vector<surface>& surfaces) {
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const surface& m = surfaces[i];
        for (int c = 0; c < 3; ++c) {
            if (!(m.albedo[c] >= 0.0f && m.albedo[c] <= 1.0f))
                throw std::invalid_argument("path_radiance: surface " + std::to_string(i) +
                                            " has an albedo outside [0, 1]");
            if (!(m.emission[c] >= 0.0f) || !std::isfinite(m.emission[c]))
                throw std::invalid_argument("path_radiance: surface " + std::to_string(i) +
                                            " has a negative or non-finite emission");
        }
    }
}

bool is_black(const color& c) { return !(c.r > 0.0f || c.g > 0.0f || c.b > 0.0f); }

}  // namespace

template <class T>
color path_radiance(const path_scene<T>& s, const ray<T>& camera_ray, const interval<T>& camera_range,
                    const std::vector<bounce_numbers<T>>& numbers, const path_settings& settings) {
    check_surfaces(s.surfaces);
    color radiance(0.0f);
    color beta(1.0f);
    ray<T> r = camera_ray;
    interval<T> range = camera_range;
    bool light_sampled = false;  // did the vertex before this one sample the lights?
    for (size_t k = 0; k < numbers.size(); ++k) {
        const bounce_numbers<T>& u = numbers[k];
        const std::optional<surface_hit<T>> hit = closest_surface(s, r, range);
        if (!hit) {
            radiance += beta * s.background;
            break;
        }
        const surface& m = hit->material;
        // A light reached by a bounce was already counted by the light sample at the vertex before.
        const bool counted_by_light_sample = light_sampled && is_light(s, hit->hit.object);
        if (!counted_by_light_sample) radiance += beta * m.emission;
        range = interval<T>{T(0), infinity<T>};
        if (m.ior > 0.0f) {  // glass: a specular vertex, no light sample; the light it leads to counts
            r = glass_bounce(s, *hit, r, u.bounce_u1);
            light_sampled = false;
            continue;
        }
        if (is_black(m.albedo)) break;

        const vec3<T>& n = hit->hit.normal;
        const vec3<T> p = ch06::shadow_ray_origin(hit->hit.point, n, n);
        if (settings.next_event) {
            for (size_t i = 0; i < s.lights.size(); ++i) {
                const light_sample<T> l = sample_light(s, i, p, u.light_u1, u.light_u2);
                if (l.pdf > T(0) && light_visible(s, p, l)) radiance += beta * light_contribution(m.albedo, n, l);
            }
        }
        light_sampled = settings.next_event;

        direction_sample<T> next;
        if (settings.cosine_sampling) {
            next = cosine_hemisphere(n, u.bounce_u1, u.bounce_u2);
        } else {
            next.direction = uniform_hemisphere(n, u.bounce_u1, u.bounce_u2);
            next.pdf = uniform_hemisphere_pdf<T>;
        }
        const T cos_theta = dot(n, next.direction);
        if (!(next.pdf > T(0)) || !(cos_theta > T(0))) break;  // a grazing draw carries nothing
        beta *= m.albedo * float(cos_theta / (pi<T> * next.pdf));

        if (int(k) >= settings.roulette_after) {
            const T w = roulette_weight(beta, u.roulette_u);
            if (!(w > T(0))) break;
            beta *= float(w);
        }
        if (is_black(beta)) break;
        r = ray<T>{p, next.direction};
    }
    return radiance;
}

template float cosine_hemisphere_pdf(const vec3<float>&, const vec3<float>&);
template double cosine_hemisphere_pdf(const vec3<double>&, const vec3<double>&);
template direction_sample<float> cosine_hemisphere(const vec3<float>&, float, float);
template direction_sample<double> cosine_hemisphere(const vec3<double>&, double, double);
template color light_contribution(const color&, const vec3<float>&, const light_sample<float>&);
template color light_contribution(const color&, const vec3<double>&, const light_sample<double>&);
template float roulette_weight(const color&, float);
template double roulette_weight(const color&, double);
template color path_radiance(const path_scene<float>&, const ray<float>&, const interval<float>&,
                             const std::vector<bounce_numbers<float>>&, const path_settings&);
template color path_radiance(const path_scene<double>&, const ray<double>&, const interval<double>&,
                             const std::vector<bounce_numbers<double>>&, const path_settings&);

}  // namespace rt::ch12
