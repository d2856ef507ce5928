// Hidden tests for chapter 11 (run by the autograder only).
//
// Failure messages name the idea that went wrong but never the expected
// numbers: every check is a plain bool computed beforehand. Random cases use
// fixed seeds, so a failure can be reproduced; references are computed in
// long double from the same rounded inputs.
#include "11-sampling/sampling.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace rt;
using namespace rt::ch11;

namespace {

using ld = long double;
const ld pi_ld = 3.14159265358979323846264338327950288L;

template <class T>
ld tolerance() {
    return sizeof(T) == 4 ? 2e-4L : 1e-9L;
}

template <class T>
bool agrees(ld got, ld want, ld scale = 1) {
    return std::isfinite(got) && std::fabs(got - want) <= tolerance<T>() * std::fmax(scale, std::fabs(want));
}

template <class T>
struct random_source {
    std::mt19937_64 gen;
    explicit random_source(unsigned long long seed) : gen(seed) {}
    T uniform(T lo, T hi) { return std::uniform_real_distribution<T>(lo, hi)(gen); }
    vec2<T> unit_square() {
        vec2<T> u(uniform(0, 1), uniform(0, 1));
        if (!(u.x < T(1))) u.x = 0;
        if (!(u.y < T(1))) u.y = 0;
        return u;
    }
};

// 1 - cos(theta_max) of the cone `from` sees the light in, in long double.
template <class T>
ld reference_one_minus_cos(const sphere<T>& light, const vec3<T>& from) {
    const ld dx = ld(light.center.x) - ld(from.x), dy = ld(light.center.y) - ld(from.y),
             dz = ld(light.center.z) - ld(from.z);
    const ld s = ld(light.radius) * ld(light.radius) / (dx * dx + dy * dy + dz * dz);
    return s / (1 + std::sqrt(1 - s));
}

template <class T>
ld reference_pdf(const sphere<T>& light, const vec3<T>& from) {
    return 1 / (2 * pi_ld * reference_one_minus_cos(light, from));
}

// The midpoint rule for the integral of sphere_light_pdf over all directions
// (see the public test): exact up to rounding because the rim is a cell edge.
template <class T>
ld integrated_density(const sphere<T>& light, const vec3<T>& from, int cells, int angles) {
    const vec3<T> axis = normalize(light.center - from);
    const vec3<T> helper = std::fabs(axis.x) > T(0.5) ? vec3<T>(0, 1, 0) : vec3<T>(1, 0, 0);
    const vec3<T> t = normalize(cross(helper, axis)), b = cross(axis, t);
    const ld cos_max = 1 - reference_one_minus_cos(light, from);
    ld total = 0;
    for (int part = 0; part < 2; ++part) {
        const ld lo = part == 0 ? cos_max : -1, hi = part == 0 ? 1 : cos_max;
        const ld dc = (hi - lo) / cells;
        for (int i = 0; i < cells; ++i) {
            const ld c = lo + (i + 0.5L) * dc, s = std::sqrt(1 - c * c);
            for (int j = 0; j < angles; ++j) {
                const ld phi = 2 * pi_ld * (j + 0.37L) / angles;
                const vec3<T> dir = T(s * std::cos(phi)) * t + T(s * std::sin(phi)) * b + T(c) * axis;
                total += ld(sphere_light_pdf(light, from, dir)) * dc * (2 * pi_ld / angles);
            }
        }
    }
    return total;
}

template <class T>
pinhole_camera<T> hidden_camera() {
    return pinhole_camera<T>(camera_frame<T>::look_at({-1, T(2.5), 4}, {T(0.3), 0, -1}, {0, 1, 0}), T(55), 90, 70);
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: stratified: every stratum of every grid gets exactly one sample", T, RT_SCALARS) {
    random_source<T> rnd(1101);
    const T below_one = std::nextafter(T(1), T(0));
    bool one_each = true, inside = true;
    for (int n : {1, 2, 5, 11, 16, 33, 64}) {
        for (int trial = 0; trial < 3; ++trial) {
            std::vector<int> count(size_t(n * n), 0);
            for (int k = 0; k < n * n; ++k) {
                vec2<T> u = rnd.unit_square();
                if (trial == 1) u = vec2<T>(below_one, below_one);
                if (trial == 2) u = vec2<T>(0, below_one);
                const vec2<T> s = stratified_sample(k, n, u);
                const int i = k % n, j = k / n;
                const bool in_x = T(i) / T(n) <= s.x && s.x < T(i + 1) / T(n);
                const bool in_y = T(j) / T(n) <= s.y && s.y < T(j + 1) / T(n);
                inside = inside && in_x && in_y;
                if (in_x && in_y) ++count[size_t(k)];
            }
            for (int c : count) one_each = one_each && c == 1;
        }
    }
    CHECK_MESSAGE(inside, "a stratified sample must lie in its own half-open stratum (strata overlap)");
    CHECK_MESSAGE(one_each, "n x n stratified samples put exactly one sample in each stratum");
}

TEST_CASE_TEMPLATE("hidden: stratified: the jitter is (i + u) / n", T, RT_SCALARS) {
    random_source<T> rnd(1102);
    bool exact = true;
    for (int trial = 0; trial < 500; ++trial) {
        const int n = 1 + int(rnd.uniform(0, 40));
        const int k = int(rnd.uniform(0, T(n * n))) % (n * n);
        const vec2<T> u(rnd.uniform(0, T(0.99)), rnd.uniform(0, T(0.99)));
        const vec2<T> s = stratified_sample(k, n, u);
        exact = exact && s.x == (T(k % n) + u.x) / T(n) && s.y == (T(k / n) + u.y) / T(n);
    }
    CHECK_MESSAGE(exact, "away from the strata's upper edges the sample is exactly ((i + u.x) / n, (j + u.y) / n)");
}

TEST_CASE_TEMPLATE("hidden: stratified: arguments outside the contract are refused", T, RT_SCALARS) {
    bool refused = true;
    const auto refuses = [](auto&& call) {
        try {
            call();
        } catch (const std::invalid_argument&) {
            return true;
        }
        return false;
    };
    refused = refused && refuses([] { stratified_sample(9, 3, vec2<T>(0, 0)); });
    refused = refused && refuses([] { stratified_sample(0, 5000, vec2<T>(0, 0)); });
    refused = refused && refuses([] { stratified_sample(0, 2, vec2<T>(T(-0.1), 0)); });
    refused = refused && refuses([] { stratified_sample(0, 2, vec2<T>(0, std::numeric_limits<T>::infinity())); });
    CHECK_MESSAGE(refused, "a stratum that does not exist or a u outside [0,1)^2 is refused with invalid_argument");
}

TEST_CASE_TEMPLATE("hidden: filter: box and tent weights", T, RT_SCALARS) {
    random_source<T> rnd(1103);
    bool box = true, tent = true;
    for (int trial = 0; trial < 400; ++trial) {
        const vec2<T> o(rnd.uniform(T(-1.5), T(1.5)), rnd.uniform(T(-1.5), T(1.5)));
        const T want_box = (o.x >= T(-0.5) && o.x < T(0.5) && o.y >= T(-0.5) && o.y < T(0.5)) ? T(1) : T(0);
        box = box && filter_weight(filter_kind::box, o) == want_box;
        const ld wx = std::fmax(0.0L, 1 - std::fabs(ld(o.x))), wy = std::fmax(0.0L, 1 - std::fabs(ld(o.y)));
        const T got = filter_weight(filter_kind::tent, o);
        tent = tent && got >= T(0) && agrees<T>(got, wx * wy);
    }
    CHECK_MESSAGE(box, "the box filter weighs 1 inside [-1/2, 1/2)^2 and 0 outside");
    CHECK_MESSAGE(tent, "the tent filter is (1 - |x|)(1 - |y|) inside (-1, 1)^2 and 0 outside, never negative");
}

TEST_CASE_TEMPLATE("hidden: filter: the estimate is the weighted mean of the samples", T, RT_SCALARS) {
    random_source<T> rnd(1104);
    bool mean = true, constant = true;
    for (int trial = 0; trial < 60; ++trial) {
        const filter_kind f = trial % 2 ? filter_kind::tent : filter_kind::box;
        const int count = 1 + trial % 17;
        std::vector<pixel_sample<T>> samples;
        ld sw = 0, sr = 0;
        const color flat(0.2f + 0.01f * float(trial), 0.7f, 3.5f);
        std::vector<pixel_sample<T>> flat_samples;
        for (int k = 0; k < count; ++k) {
            const vec2<T> o((rnd.uniform(0, 1) * 2 - 1) * filter_radius<T>(f),
                            (rnd.uniform(0, 1) * 2 - 1) * filter_radius<T>(f));
            const float value = float(rnd.uniform(0, 4));
            samples.push_back({o, color(value, 0.0f, 1.0f)});
            flat_samples.push_back({o, flat});
            const ld w = ld(filter_weight(f, o));
            sw += w, sr += w * value;
        }
        const color c = pixel_estimate(f, samples);
        if (sw > 0) mean = mean && agrees<float>(c.r, sr / sw) && agrees<float>(c.b, 1.0L);
        const color e = pixel_estimate(f, flat_samples);
        if (sw > 0)
            constant = constant && agrees<float>(e.r, flat.r) && agrees<float>(e.g, flat.g) && agrees<float>(e.b, flat.b);
    }
    CHECK_MESSAGE(mean, "a pixel's estimate is sum w value / sum w, with the filter's weights");
    CHECK_MESSAGE(constant, "a pixel of constant colour keeps that colour under every filter");
}

TEST_CASE_TEMPLATE("hidden: light: the sample's density is per steradian and exact", T, RT_SCALARS) {
    random_source<T> rnd(1105);
    bool density = true, consistent = true;
    for (int trial = 0; trial < 200; ++trial) {
        const sphere<T> light{{rnd.uniform(-5, 5), rnd.uniform(-5, 5), rnd.uniform(-5, 5)}, rnd.uniform(T(0.1), 2), 0};
        const vec3<T> from(rnd.uniform(-5, 5), rnd.uniform(-5, 5), rnd.uniform(-5, 5));
        const auto s = sample_sphere_light(light, from, rnd.unit_square());
        const T d = length(light.center - from);
        if (!(d > light.radius * T(1.01))) continue;
        if (!s) {
            density = false;
            continue;
        }
        density = density && agrees<T>(s->pdf, reference_pdf(light, from));
        const T pdf = sphere_light_pdf(light, from, s->direction * T(3));
        consistent = consistent && (pdf == T(0) || agrees<T>(pdf, s->pdf));
    }
    CHECK_MESSAGE(density, "the density of a direction uniform in the light's cone is 1 / (2 pi (1 - cos theta_max)) "
                           "per steradian");
    CHECK_MESSAGE(consistent, "sphere_light_pdf gives the sampled direction the density the sample carries");
}

TEST_CASE_TEMPLATE("hidden: light: the density integrates to 1 (quadrature)", T, RT_SCALARS) {
    bool one = true;
    const vec3<T> from(T(0.5), T(-0.25), T(1));
    for (const sphere<T>& light : {sphere<T>{{0, 4, 0}, T(2), 0}, sphere<T>{{-3, 1, 2}, T(0.4), 0},
                                   sphere<T>{{1, 0, 1}, T(0.45), 0}})
        one = one && std::fabs(integrated_density(light, from, 48, 12) - 1) < 1e-3L;
    CHECK_MESSAGE(one, "sphere_light_pdf integrates to 1 over the sphere of directions");
}

TEST_CASE_TEMPLATE("hidden: light: points lie on the light, in its cone, facing the point", T, RT_SCALARS) {
    random_source<T> rnd(1106);
    bool on_light = true, in_cone = true, along = true, facing = true;
    for (int trial = 0; trial < 300; ++trial) {
        const sphere<T> light{{rnd.uniform(-3, 3), rnd.uniform(1, 6), rnd.uniform(-3, 3)}, rnd.uniform(T(0.05), 1), 0};
        const vec3<T> from(rnd.uniform(-3, 3), rnd.uniform(-1, 0), rnd.uniform(-3, 3));
        vec2<T> u = rnd.unit_square();
        if (trial % 10 == 0) u.x = std::nextafter(T(1), T(0));  // the rim
        const auto s = sample_sphere_light(light, from, u);
        if (!s) {
            on_light = false;
            continue;
        }
        const ld r = ld(light.radius);
        on_light = on_light && agrees<T>(ld(length(s->point - light.center)), r, 1);
        const ld cos_max = 1 - reference_one_minus_cos(light, from);
        const ld c = ld(dot(s->direction, normalize(light.center - from)));
        in_cone = in_cone && c >= cos_max - 8 * tolerance<T>();
        along = along && agrees<T>(ld(length(s->point - (from + s->distance * s->direction))), 0, 1) &&
                agrees<T>(ld(length(s->direction)), 1);
        facing = facing && ld(dot(s->normal, s->direction)) <= 10 * std::sqrt(tolerance<T>()) &&
                 agrees<T>(ld(length(s->normal)), 1);
    }
    CHECK_MESSAGE(on_light, "a light sample's point lies on the light's surface");
    CHECK_MESSAGE(in_cone, "a light sample's direction lies inside the cone the light subtends");
    CHECK_MESSAGE(along, "point = from + distance * unit direction");
    CHECK_MESSAGE(facing, "the point is the near side's, with the light's outward unit normal");
}

TEST_CASE_TEMPLATE("hidden: light: directions spread uniformly over the cone", T, RT_SCALARS) {
    // cos(theta) = 1 - u.x (1 - cos theta_max): half the cone's solid angle lies below u.x = 1/2.
    const sphere<T> light{{0, 0, -4}, T(2), 0};
    const vec3<T> from(0, 0, 0);
    const ld omc = reference_one_minus_cos(light, from);
    bool uniform = true;
    for (T ux : {T(0), T(0.25), T(0.5), T(0.9)}) {
        const auto s = sample_sphere_light(light, from, vec2<T>(ux, T(0.3)));
        uniform = uniform && s && agrees<T>(ld(-s->direction.z), 1 - ld(ux) * omc);
    }
    CHECK_MESSAGE(uniform, "a direction uniform in solid angle has cos(theta) uniform between cos(theta_max) and 1");
}

TEST_CASE_TEMPLATE("hidden: light: small far lights keep their digits", T, RT_SCALARS) {
    bool accurate = true;
    for (T far : {T(50), T(400), T(3000), sizeof(T) == 4 ? T(1e4) : T(1e7)}) {
        const sphere<T> light{{far, 0, 0}, T(1), 0};
        const auto s = sample_sphere_light(light, vec3<T>(0, 0, 0), vec2<T>(T(0.2), T(0.9)));
        accurate = accurate && s && std::fabs(ld(s->pdf) / reference_pdf(light, vec3<T>(0, 0, 0)) - 1) < 1e-4L;
    }
    CHECK_MESSAGE(accurate, "1 - cos(theta_max) of a small far light must not cancel");
}

TEST_CASE_TEMPLATE("hidden: light: no cone from inside, bad lights refused", T, RT_SCALARS) {
    const sphere<T> light{{1, 1, 1}, T(2), 0};
    bool inside = !sample_sphere_light(light, vec3<T>(T(1.5), 1, 1), vec2<T>(0, 0)).has_value() &&
                  sphere_light_pdf(light, vec3<T>(1, 1, 2), vec3<T>(0, 1, 0)) == T(0);
    bool refused = false;
    try {
        sample_sphere_light(sphere<T>{{0, 0, 0}, -T(1), 0}, vec3<T>(5, 0, 0), vec2<T>(0, 0));
    } catch (const std::invalid_argument&) {
        refused = true;
    }
    CHECK_MESSAGE(inside, "a point inside the light has no cone: nullopt, density 0");
    CHECK_MESSAGE(refused, "a light whose radius is not > 0 is refused");
}

TEST_CASE_TEMPLATE("hidden: lens: aperture 0 is the pinhole camera bit for bit", T, RT_SCALARS) {
    const pinhole_camera<T> cam = hidden_camera<T>();
    bool same = true;
    for (int row = 0; row < cam.height; row += 3)
        for (int col = 0; col < cam.width; col += 4) {
            const ray<T> want = cam.primary_ray(col, row);
            const ray<T> got = thin_lens_ray(cam, thin_lens<T>{T(0), T(7)}, T(col) + T(0.5), T(row) + T(0.5),
                                             vec2<T>(T(0.9), T(0.1)));
            same = same && got.origin == want.origin && got.direction == want.direction;
        }
    CHECK_MESSAGE(same, "a lens of aperture 0 gives exactly the pinhole camera's rays");
}

TEST_CASE_TEMPLATE("hidden: lens: the lens sample is scaled by the aperture", T, RT_SCALARS) {
    const pinhole_camera<T> cam = hidden_camera<T>();
    random_source<T> rnd(1107);
    bool on_disc = true, reaches_rim = false, through_focus = true;
    for (T aperture : {T(0.01), T(0.5), T(2)}) {
        const thin_lens<T> lens{aperture, T(3.5)};
        for (int trial = 0; trial < 100; ++trial) {
            const vec2<T> u = trial == 0 ? vec2<T>(std::nextafter(T(1), T(0)), T(0.3)) : rnd.unit_square();
            const T px = rnd.uniform(0, 90), py = rnd.uniform(0, 70);
            const ray<T> r = thin_lens_ray(cam, lens, px, py, u);
            const ld off = ld(length(r.origin - cam.frame.eye));
            on_disc = on_disc && off <= ld(aperture) * (1 + tolerance<T>()) &&
                      agrees<T>(off, ld(aperture) * std::sqrt(ld(u.x)), ld(aperture));
            if (trial == 0) reaches_rim = reaches_rim || off > 0.99L * ld(aperture);
            const ray<T> pin = thin_lens_ray(cam, thin_lens<T>{T(0), T(3.5)}, px, py, u);
            through_focus = through_focus && rt::test::close(r.origin + T(3.5) * r.direction,
                                                             pin.origin + T(3.5) * pin.direction);
        }
    }
    CHECK_MESSAGE(on_disc, "lens points lie at aperture * sqrt(u.x) from the eye: on the lens's disc");
    CHECK_MESSAGE(reaches_rim, "lens points reach the rim of the aperture");
    CHECK_MESSAGE(through_focus, "every lens ray passes through the point in focus at t = focus_distance");
}

TEST_CASE_TEMPLATE("hidden: lens: bad lenses are refused", T, RT_SCALARS) {
    const pinhole_camera<T> cam = hidden_camera<T>();
    int refused = 0;
    for (const thin_lens<T>& lens : {thin_lens<T>{-T(0.1), T(1)}, thin_lens<T>{T(0.1), T(0)},
                                     thin_lens<T>{std::numeric_limits<T>::quiet_NaN(), T(1)}}) {
        try {
            thin_lens_ray(cam, lens, T(1), T(1), vec2<T>(0, 0));
        } catch (const std::invalid_argument&) {
            ++refused;
        }
    }
    CHECK_MESSAGE(refused == 3, "a negative or NaN aperture, or a focus distance that is not > 0, is refused");
}
