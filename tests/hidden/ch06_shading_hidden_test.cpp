// Hidden tests for chapter 06 (run by the autograder only).
//
// Failure messages name the idea that went wrong but never the expected
// numbers: every check is a plain bool computed beforehand. Random cases use
// fixed seeds, so a failure can be reproduced.
#include "04-plane/plane.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "06-shading/shading.hpp"
#include "02-sphere/sphere.hpp"
#include "05-triangle/triangle.hpp"

#include "common/camera.hpp"
#include "rpc/served.hpp"
#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace rt;

namespace {

using ld = long double;

template <class T>
T eps() {
    return std::numeric_limits<T>::epsilon();
}

// Relative agreement suited to T (geometry in T, colours in float).
template <class T>
bool agrees(ld got, ld want) {
    const ld tol = sizeof(T) == 4 ? 1e-4L : 1e-9L;
    return std::isfinite(got) && std::fabs(got - want) <= tol * (1 + std::fabs(want));
}

bool colour_agrees(const color& got, ld r, ld g, ld b, ld tol = 1e-4L) {
    auto one = [tol](float x, ld want) {
        return std::isfinite(x) && std::fabs(ld(x) - want) <= tol * (1 + std::fabs(want));
    };
    return one(got.r, r) && one(got.g, g) && one(got.b, b);
}

bool finite_non_negative(const color& c) {
    return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

template <class T>
struct random_source {
    std::mt19937_64 gen;
    explicit random_source(unsigned long long seed) : gen(seed) {}
    T uniform(T lo, T hi) { return std::uniform_real_distribution<T>(lo, hi)(gen); }
    // A random direction of random length in [lo_len, hi_len] (log-uniform).
    vec3<T> direction(T lo_len = T(1e-2), T hi_len = T(1e2)) {
        vec3<T> v;
        do {
            v = vec3<T>(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
        } while (!(dot(v, v) > T(0.01) && dot(v, v) < T(1)));
        const T len = std::exp(uniform(std::log(lo_len), std::log(hi_len)));
        return v / length(v) * len;
    }
};

// Long double references, from the same rounded inputs.
template <class T>
ld ld_dot(const vec3<T>& a, const vec3<T>& b) {
    return ld(a.x) * ld(b.x) + ld(a.y) * ld(b.y) + ld(a.z) * ld(b.z);
}

template <class T>
ld ld_len(const vec3<T>& a) {
    return std::sqrt(ld_dot(a, a));
}

template <class T>
ld reference_lambert(const vec3<T>& n, const vec3<T>& l) {
    const ld c = ld_dot(n, l) / (ld_len(n) * ld_len(l));
    return c > 0 ? std::fmin(c, ld(1)) : ld(0);
}

template <class T>
ld reference_blinn_phong(const vec3<T>& n, const vec3<T>& l, const vec3<T>& v, ld shininess) {
    if (!(ld_dot(n, l) > 0)) return 0;
    const ld ll = ld_len(l), lv = ld_len(v);
    const ld hx = ld(l.x) / ll + ld(v.x) / lv, hy = ld(l.y) / ll + ld(v.y) / lv, hz = ld(l.z) / ll + ld(v.z) / lv;
    const ld hl = std::sqrt(hx * hx + hy * hy + hz * hz);
    if (!(hl > 0)) return 0;
    const ld c = (ld(n.x) * hx + ld(n.y) * hy + ld(n.z) * hz) / (ld_len(n) * hl);
    return c > 0 ? std::pow(std::fmin(c, ld(1)), shininess) : ld(0);
}

// The plain occlusion tests, served ones (tests/support/rpc/served.hpp): the
// judge answers the shadow rays shade() may ask (the student's own
// shadow_ray() for each light) and notes any other question.
template <class T>
ch06::occlusion_test<T> nothing_blocks() {
    return rt::test::nothing_blocks<T>();
}

template <class T>
ch06::occlusion_test<T> everything_blocks() {
    return rt::test::everything_blocks<T>();
}

material glossy(color diffuse, color specular, float shininess) {
    material m;
    m.diffuse = diffuse;
    m.specular = specular;
    m.shininess = shininess;
    return m;
}

// --- a small test scene, rendered with the reference loop -------------------

template <class T>
struct test_scene {
    std::vector<sphere<T>> spheres;
    std::vector<plane<T>> planes;
    std::vector<triangle<T>> triangles;
    std::vector<vec3<T>> lights;
    vec3<T> eye, target;

    int count() const { return int(spheres.size() + planes.size() + triangles.size()); }

    std::optional<hit_record<T>> intersect(int i, const ray<T>& r, const interval<T>& range) const {
        size_t k = size_t(i);
        if (k < spheres.size()) return ch02::intersect_sphere(spheres[k], r, range);
        k -= spheres.size();
        if (k < planes.size()) return ch04::intersect_plane(planes[k], r, range);
        return ch05::intersect_triangle(triangles[k - planes.size()], r, range);
    }
};

// Spheres, a ground plane and a tetrahedron of size `scale`, moved by `shift`.
template <class T>
test_scene<T> make_scene(T scale, vec3<T> shift) {
    test_scene<T> s;
    auto at = [&](T x, T y, T z) { return shift + scale * vec3<T>(x, y, z); };
    s.spheres = {{at(-1, 1, -5), scale, 0}, {at(1.5, T(0.6), -4), T(0.6) * scale, 0}};
    s.planes = {{at(0, 0, 0), {0, 1, 0}, 0}};
    const vec3<T> a = at(0, 0, -7), b = at(2, 0, -8), c = at(T(0.5), 0, -9), d = at(T(0.8), 2, T(-7.8));
    s.triangles = {{a, c, b, 0}, {a, b, d, 0}, {b, c, d, 0}, {c, a, d, 0}};
    s.lights = {at(-4, 6, 1), at(5, 3, -2)};
    s.eye = at(0, T(1.5), 1);
    s.target = at(0, T(0.7), -5);
    return s;
}

// Renders the scene with the reference loop and, for every hit and every
// light above it, asks the student's shadow_ray() for the shadow ray from that
// hit (the one shade() asks about, shading.hpp) and counts those that hit the
// very object they leave. Every object is convex, so a shadow ray leaving a
// lit point can never truly re-enter it: each such hit is shadow acne. `lit`
// counts the shadow rays checked.
template <class T>
long count_acne(const test_scene<T>& s, int width, int height, long& lit) {
    auto frame = camera_frame<T>::look_at(s.eye, s.target, {0, 1, 0});
    pinhole_camera<T> camera(frame, T(55), width, height);
    rt::test::served_objects<T> intersect;
    intersect.count = s.count();
    intersect.test = [&s](int i, const ray<T>& r, const interval<T>& range) { return s.intersect(i, r, range); };
    long acne = 0;
    lit = 0;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const ray<T> r = camera.primary_ray(col, row);
            // (0, inf) rather than t > 1: the tiny scene lies entirely between the eye and an image
            // plane at distance 1. Nothing in these scenes is behind the eye.
            auto hit = ch03::closest_hit(s.count(), ch03::object_intersector<T>(intersect), r,
                                         interval<T>{T(0), infinity<T>});
            if (!hit) continue;
            // The normal on the viewer's side, as a chapter program passes it to shade().
            const vec3<T> facing = hit->facing_normal(r);
            for (const vec3<T>& light : s.lights) {
                if (!(dot(light - hit->point, facing) > T(0))) continue;  // below the surface: no shadow ray
                const ch06::shadow_query<T> q = ch06::shadow_ray(hit->point, facing, light);
                // Only shadow rays that leave the lit side are about acne; a shadow ray
                // sent into the surface is a different mistake, tested elsewhere.
                if (!(dot(q.r.direction, facing) > T(0))) continue;
                ++lit;
                if (s.intersect(hit->object, q.r, q.range)) ++acne;
            }
        }
    return acne;
}

}  // namespace

// --- Lambert ----------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: lambert matches the cosine law on random directions", T, RT_SCALARS) {
    random_source<T> rnd(601);
    bool ok = true;
    for (int i = 0; i < 2000 && ok; ++i) {
        const vec3<T> n = rnd.direction(), l = rnd.direction(T(1e-3), T(1e4));
        ok = agrees<T>(ch06::lambert(n, l), reference_lambert(n, l));
    }
    CHECK_MESSAGE(ok, "Lambert's term is the cosine of the angle between the normal and the light direction "
                      "(both made unit length) clamped at zero");
}

TEST_CASE_TEMPLATE("hidden: lambert is zero for lights below the surface", T, RT_SCALARS) {
    random_source<T> rnd(602);
    bool ok = true;
    for (int i = 0; i < 1000 && ok; ++i) {
        const vec3<T> n = rnd.direction(), l = rnd.direction();
        if (dot(n, l) < T(0)) ok = ch06::lambert(n, l) == T(0);
    }
    CHECK_MESSAGE(ok, "a light below the surface (negative cosine) must give exactly zero, never a negative amount");
}

TEST_CASE_TEMPLATE("hidden: lambert stays between zero and one and never NaN", T, RT_SCALARS) {
    random_source<T> rnd(603);
    const T nan = std::numeric_limits<T>::quiet_NaN();
    std::vector<vec3<T>> odd = {vec3<T>(0), vec3<T>(nan, 0, 1), vec3<T>(infinity<T>, 1, 0),
                                vec3<T>(T(1e-30), 0, 0), vec3<T>(T(1e30), T(1e30), 0)};
    for (int i = 0; i < 200; ++i) odd.push_back(rnd.direction(T(1e-6), T(1e6)));
    bool ok = true;
    for (const auto& a : odd)
        for (const auto& b : odd) {
            const T c = ch06::lambert(a, b);
            ok = ok && c >= T(0) && c <= T(1) + T(4) * eps<T>();  // NaN fails both comparisons
        }
    CHECK_MESSAGE(ok, "Lambert's term is a cosine clamped at zero: always in [0, 1], and an unusable input "
                      "(zero length, NaN, infinity) must give 0, not NaN");
}

// --- Blinn-Phong ----------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: blinn phong matches the half vector formula", T, RT_SCALARS) {
    random_source<T> rnd(604);
    bool ok = true;
    for (int i = 0; i < 2000 && ok; ++i) {
        const vec3<T> n = rnd.direction(), l = rnd.direction(T(1e-2), T(1e3)), v = rnd.direction(T(1e-2), T(1e3));
        const T shininess = rnd.uniform(T(1), T(200));
        const ld want = reference_blinn_phong(n, l, v, ld(shininess));
        const T got = ch06::blinn_phong(n, l, v, shininess);
        const ld tol = sizeof(T) == 4 ? 2e-3L : 1e-8L;
        ok = std::isfinite(got) && std::fabs(ld(got) - want) <= tol * (want + ld(1e-6));
    }
    CHECK_MESSAGE(ok, "the highlight is (n . h)^shininess with h the normalised sum of the UNIT light and viewer "
                      "directions (the half vector), with n unit length too");
}

TEST_CASE_TEMPLATE("hidden: blinn phong is zero for lights below the surface", T, RT_SCALARS) {
    random_source<T> rnd(605);
    bool ok = true;
    for (int i = 0; i < 1000 && ok; ++i) {
        const vec3<T> n = rnd.direction(), l = rnd.direction(), v = rnd.direction();
        if (dot(n, l) < T(0)) ok = ch06::blinn_phong(n, l, v, T(10)) == T(0);
    }
    CHECK_MESSAGE(ok, "a light below the surface makes no highlight, wherever the viewer is");
}

TEST_CASE_TEMPLATE("hidden: blinn phong stays in range and never NaN", T, RT_SCALARS) {
    const vec3<T> n(0, 1, 0);
    const T a = ch06::blinn_phong(n, vec3<T>(1, 1, 0), vec3<T>(-1, -1, 0), T(20));  // light and viewer opposite
    const T b = ch06::blinn_phong(n, vec3<T>(1, 1, 0), vec3<T>(0), T(20));          // zero viewer vector
    const T c = ch06::blinn_phong(vec3<T>(0), vec3<T>(1, 1, 0), vec3<T>(0, 1, 0), T(20));
    const T d = ch06::blinn_phong(n, vec3<T>(1, 1, 0), vec3<T>(-1, 1, 0), T(0));      // shininess 0
    const bool ok = a == T(0) && b == T(0) && c == T(0) && agrees<T>(d, 1);
    CHECK_MESSAGE(ok, "the highlight is always in [0, 1]: no NaN when the half vector or an input is zero, "
                      "and a shininess of 0 is a valid (completely dull) material");
}

TEST_CASE_TEMPLATE("hidden: blinn phong rejects a negative shininess", T, RT_SCALARS) {
    bool threw = false;
    try {
        (void)ch06::blinn_phong(vec3<T>(0, 1, 0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 0), T(-2));
    } catch (const std::invalid_argument&) {
        threw = true;
    }
    CHECK_MESSAGE(threw, "a negative shininess is a bad material: throw std::invalid_argument");
}

// --- the shadow ray -------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: the shadow ray origin lies on the light side", T, RT_SCALARS) {
    random_source<T> rnd(606);
    bool ok = true;
    for (int i = 0; i < 2000 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-2), T(1e4)), n = rnd.direction(), to_light = rnd.direction();
        const vec3<T> o = ch06::shadow_ray_origin(p, n, to_light);
        const ld moved = ld_dot(o - p, n);
        ok = is_finite(o) && (dot(n, to_light) >= T(0) ? moved > 0 : moved < 0);
    }
    // A light exactly in the tangent plane (dot(normal, to_light) = 0, or -0): the header's rule says
    // s = +1, along +normal.
    bool tangent_ok = true;
    const vec3<T> n{T(0), T(3), T(4)};
    for (const vec3<T>& l : {vec3<T>(1, 0, 0), vec3<T>(-1, 0, 0), vec3<T>(0, 4, -3), vec3<T>(5, -8, 6)}) {
        const vec3<T> p{T(2), T(-3), T(0.5)};
        const vec3<T> o = ch06::shadow_ray_origin(p, n, l);
        tangent_ok = tangent_ok && is_finite(o) && ld_dot(o - p, n) > 0;
    }
    CHECK_MESSAGE(ok, "the shadow ray's origin moves off the surface towards the side the light is on "
                      "(along +normal or -normal)");
    CHECK_MESSAGE(tangent_ok, "a light exactly in the surface's tangent plane (dot(normal, to_light) = 0) counts "
                              "as on the normal's side: s = +1");
}

TEST_CASE_TEMPLATE("hidden: the shadow ray origin moves along the normal only", T, RT_SCALARS) {
    random_source<T> rnd(607);
    bool ok = true;
    for (int i = 0; i < 1000 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-1), T(1e2)), n = rnd.direction(), to_light = rnd.direction();
        const vec3<T> o = ch06::shadow_ray_origin(p, n, to_light);
        const vec3<T> step = o - p;
        // Parallel to n: the cross product is tiny compared with |step| |n|.
        ok = is_finite(o) && length(cross(step, n)) <= T(1e-2) * length(step) * length(n);
    }
    CHECK_MESSAGE(ok, "the offset is along the surface normal: moving sideways along the surface does not "
                      "take the origin away from the surface");
}

TEST_CASE_TEMPLATE("hidden: the shadow offset grows with the size of the coordinates", T, RT_SCALARS) {
    bool ok = true;
    for (T magnitude : {T(1e-4), T(1e-2), T(1), T(30), T(1e3), T(1e5), T(1e7)}) {
        const vec3<T> p(magnitude, T(-0.5) * magnitude, T(0.25) * magnitude);
        const vec3<T> n = normalize(vec3<T>(1, 2, 3));
        const vec3<T> o = ch06::shadow_ray_origin(p, n, n);
        const ld moved = ld_dot(o - p, n);  // n is unit: the distance moved along it
        const ld scale = ld(eps<T>()) * std::fmax(ld(1), ld(magnitude));
        ok = ok && moved >= 4 * scale && moved <= 4096 * scale;
    }
    CHECK_MESSAGE(ok, "the offset must be a modest multiple of the rounding error at the point's scale: "
                      "machine epsilon times max(1, |x|, |y|, |z|). A fixed epsilon is too small for "
                      "large coordinates or too large for small ones");
}

TEST_CASE_TEMPLATE("hidden: the shadow ray origin rejects a zero normal", T, RT_SCALARS) {
    bool threw = false;
    try {
        (void)ch06::shadow_ray_origin(vec3<T>(1, 2, 3), vec3<T>(0), vec3<T>(0, 1, 0));
    } catch (const std::invalid_argument&) {
        threw = true;
    }
    CHECK_MESSAGE(threw, "a zero normal gives no direction to step off the surface: throw std::invalid_argument");
}

TEST_CASE_TEMPLATE("hidden: the shadow ray points at the light and stops there", T, RT_SCALARS) {
    random_source<T> rnd(608);
    bool ok = true;
    for (int i = 0; i < 1000 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-1), T(1e2)), n = rnd.direction();
        const vec3<T> light = p + rnd.direction(T(1e-1), T(1e2));
        const ch06::shadow_query<T> q = ch06::shadow_ray(p, n, light);
        const vec3<T> end = q.r.at(q.range.max);
        const bool unit = agrees<T>(length(q.r.direction), 1);
        const bool reaches = ld_len(vec3<T>(end - light)) <= (sizeof(T) == 4 ? 1e-4L : 1e-10L) * (1 + ld_len(light));
        const bool starts_at_origin = q.range.min == T(0);
        const bool origin_is_offset = q.r.origin == ch06::shadow_ray_origin(p, n, light - p);
        ok = unit && reaches && starts_at_origin && origin_is_offset;
    }
    CHECK_MESSAGE(ok, "the shadow ray starts at shadow_ray_origin, has a unit direction towards the light, "
                      "and its range (0, tmax) ends exactly at the light");
}

TEST_CASE_TEMPLATE("hidden: a shadow ray to a light on its origin blocks nothing", T, RT_SCALARS) {
    const vec3<T> p(1, 2, 3), n(0, 1, 0);
    const vec3<T> light = ch06::shadow_ray_origin(p, n, n);
    const ch06::shadow_query<T> q = ch06::shadow_ray(p, n, light);
    const bool ok = is_finite(q.r.direction) && !(q.range.min < q.range.max);
    CHECK_MESSAGE(ok, "a light at the shadow ray's origin: no NaN direction, and an empty range");
}

// --- shade() ----------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: shade matches the lighting formula on random points", T, RT_SCALARS) {
    random_source<T> rnd(609);
    bool ok = true;
    for (int i = 0; i < 500 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-1), T(10)), n = rnd.direction();
        vec3<T> v = rnd.direction();
        if (dot(v, n) < T(0)) v = -v;
        const material m = glossy(color(0.2f, 0.5f, 0.9f), color(0.4f, 0.3f, 0.1f), float(rnd.uniform(T(2), T(90))));
        const color ambient(0.05f, 0.1f, 0.02f);
        std::vector<point_light> lights;
        ld want[3] = {ld(ambient.r) * m.diffuse.r, ld(ambient.g) * m.diffuse.g, ld(ambient.b) * m.diffuse.b};
        for (int k = 0; k < 3; ++k) {
            const vec3<T> to_light = rnd.direction(T(0.5), T(20));
            const color intensity(float(rnd.uniform(1, 50)), float(rnd.uniform(1, 50)), float(rnd.uniform(1, 50)));
            lights.push_back({convert<double>(vec3<T>(p + to_light)), intensity});
            const vec3<T> l = convert<T>(lights.back().position) - p;  // as shade() will see it
            const ld diffuse = reference_lambert(n, l), spec = reference_blinn_phong(n, l, v, ld(m.shininess));
            const ld falloff = 1 / ld_dot(l, l);
            for (int c = 0; c < 3; ++c)
                want[c] += ld(intensity[c]) * falloff * (ld(m.diffuse[c]) * diffuse + ld(m.specular[c]) * spec);
        }
        const color got = ch06::shade(p, n, v, m, lights, ambient, nothing_blocks<T>());
        ok = colour_agrees(got, want[0], want[1], want[2], sizeof(T) == 4 ? 2e-3L : 1e-4L);
    }
    CHECK_MESSAGE(ok, "shade = ambient * diffuse + sum over lights of intensity / d^2 * (diffuse * Lambert + "
                      "specular * Blinn-Phong)");
}

TEST_CASE_TEMPLATE("hidden: light falls off with the square of the distance", T, RT_SCALARS) {
    random_source<T> rnd(610);
    bool ok = true;
    const material m = glossy(color(0.7f), color(0), 10);
    for (int i = 0; i < 200 && ok; ++i) {
        const T d = rnd.uniform(T(0.3), T(30));
        const color c = ch06::shade(vec3<T>(0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), m,
                                    {{{0, double(d), 0}, color(5)}}, color(0), nothing_blocks<T>());
        ok = colour_agrees(c, 3.5L / (ld(d) * ld(d)), 3.5L / (ld(d) * ld(d)), 3.5L / (ld(d) * ld(d)));
    }
    CHECK_MESSAGE(ok, "a point light's contribution falls off as intensity / distance^2 (inverse-square law)");
}

TEST_CASE_TEMPLATE("hidden: several lights add up", T, RT_SCALARS) {
    random_source<T> rnd(611);
    bool ok = true;
    const material m = glossy(color(0.6f, 0.4f, 0.2f), color(0.3f), 20);
    for (int i = 0; i < 200 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(0.1), T(5)), n = rnd.direction(), v = n + rnd.direction(T(0.1), T(0.5));
        const point_light a{convert<double>(vec3<T>(p + rnd.direction(T(1), T(5)))), color(3, 4, 5)};
        const point_light b{convert<double>(vec3<T>(p + rnd.direction(T(1), T(5)))), color(6, 2, 1)};
        const color amb(0.1f);
        const color both = ch06::shade(p, n, v, m, {a, b}, amb, nothing_blocks<T>());
        const color only_a = ch06::shade(p, n, v, m, {a}, amb, nothing_blocks<T>());
        const color only_b = ch06::shade(p, n, v, m, {b}, amb, nothing_blocks<T>());
        const color sum = only_a + only_b - amb * m.diffuse;
        ok = colour_agrees(both, sum.r, sum.g, sum.b);
    }
    CHECK_MESSAGE(ok, "light is additive: two lights give the sum of what each gives alone (ambient counted once)");
}

TEST_CASE_TEMPLATE("hidden: shade never exceeds what the lights deliver", T, RT_SCALARS) {
    random_source<T> rnd(612);
    bool ok = true;
    for (int i = 0; i < 1000 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-2), T(1e3)), n = rnd.direction(), v = rnd.direction();
        const material m = glossy(color(float(rnd.uniform(0, 1))), color(float(rnd.uniform(0, 1))),
                                  float(rnd.uniform(0, 200)));
        std::vector<point_light> lights;
        ld bound = 0.2L * m.diffuse.r;
        for (int k = 0; k < 4; ++k) {
            lights.push_back({convert<double>(vec3<T>(p + rnd.direction(T(1e-1), T(1e2)))), color(10)});
            const vec3<T> l = convert<T>(lights.back().position) - p;
            bound += 10 * (ld(m.diffuse.r) + ld(m.specular.r)) / ld_dot(l, l);
        }
        const color c = ch06::shade(p, n, v, m, lights, color(0.2f), nothing_blocks<T>());
        ok = finite_non_negative(c) && ld(c.r) <= bound * (1 + 1e-4L) && c.r >= 0.2f * m.diffuse.r * (1 - 1e-5f);
    }
    CHECK_MESSAGE(ok, "energy: a shaded colour is never negative, never NaN, at least the ambient part, and "
                      "never more than ambient plus (diffuse + specular) * intensity / d^2 for every light");
}

TEST_CASE_TEMPLATE("hidden: shade uses the normal as given, never turned", T, RT_SCALARS) {
    // The normal points down, the viewer and one light are above, another light is below: only the
    // light below, on the normal's side, counts (the caller's face rule chose the side, once).
    const material m = glossy(color(0.5f), color(0), 8);
    const color c = ch06::shade(vec3<T>(0), vec3<T>(0, -1, 0), vec3<T>(0, 1, 1), m,
                                {{{0, 2, 0}, color(4)}, {{0, -1, 0}, color(3)}}, color(0), nothing_blocks<T>());
    CHECK_MESSAGE(colour_agrees(c, 1.5L, 1.5L, 1.5L),
                  "shade lights the side the given normal is on and never turns it towards the viewer: the caller "
                  "passes the hit's facing normal (common/hit_record.hpp)");
}

TEST_CASE_TEMPLATE("hidden: a light below the surface sends no shadow ray", T, RT_SCALARS) {
    // No question allowed: one makes the occlusion test throw std::logic_error out of shade().
    auto no_question = rt::test::nothing_blocks<T>();
    no_question.budget = 0;
    const ch06::occlusion_test<T> counting = no_question;
    bool asked = false;
    color c(1);
    try {
        c = ch06::shade(vec3<T>(0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), glossy(color(0.5f), color(1), 8),
                        {{{0, -2, 0}, color(4)}, {{3, -1, 0}, color(4)}}, color(0), counting);
    } catch (const std::logic_error&) {
        asked = true;
    }
    CHECK_MESSAGE((!asked && c.r == 0.0f && c.g == 0.0f && c.b == 0.0f),
                  "a light below the surface contributes nothing, so there is no need to trace its shadow ray");
}

TEST_CASE_TEMPLATE("hidden: shade asks only about the segment up to the light", T, RT_SCALARS) {
    random_source<T> rnd(613);
    bool ok = true;
    for (int i = 0; i < 300 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(0.1), T(10)), n = rnd.direction();
        const vec3<T> light = p + n * T(0.01) + rnd.direction(T(0.5), T(20));
        if (!(dot(light - p, n) > T(0))) continue;
        // shade() may only ask about shadow_ray(p, n, light) (anything else throws). The answer:
        // blocked unless that segment ends at the light and starts at t >= 0, so a right question
        // leaves the point lit and a wrong segment leaves it dark.
        const auto segment_to_light = [&](const ray<T>& r, const interval<T>& range) {
            const vec3<T> end = r.at(range.max);
            return !(is_finite(end) &&
                     ld_len(vec3<T>(end - light)) <= (sizeof(T) == 4 ? 1e-4L : 1e-10L) * (1 + ld_len(light)) &&
                     !(range.min < T(0)));
        };
        const ch06::occlusion_test<T> check = rt::test::served_occlusion<T>{segment_to_light};
        try {
            const color c = ch06::shade(p, n, n, glossy(color(0.5f), color(0), 8),
                                        {{convert<double>(light), color(1)}}, color(0), check);
            ok = c.r > 0.0f;
        } catch (const std::logic_error&) {
            ok = false;
        }
    }
    CHECK_MESSAGE(ok, "the occlusion test must be asked about the shadow ray from the offset origin, with a range "
                      "that ends at the light: blockers beyond the light cast no shadow");
}

TEST_CASE_TEMPLATE("hidden: blocked lights leave only the ambient term", T, RT_SCALARS) {
    const material m = glossy(color(0.4f, 0.5f, 0.6f), color(1), 8);
    const color c = ch06::shade(vec3<T>(0), vec3<T>(0, 1, 0), vec3<T>(1, 1, 0), m,
                                {{{0, 2, 0}, color(4)}, {{-1, 1, 0}, color(9)}}, color(0.5f), everything_blocks<T>());
    CHECK_MESSAGE(colour_agrees(c, 0.2L, 0.25L, 0.3L),
                  "when every shadow ray is blocked, no light reaches the point: only ambient * diffuse remains "
                  "(the highlight is blocked too)");
}

TEST_CASE_TEMPLATE("hidden: a light on the shaded point adds nothing", T, RT_SCALARS) {
    const color c = ch06::shade(vec3<T>(1, 1, 1), vec3<T>(0, 1, 0), vec3<T>(0, 1, 0), glossy(color(0.5f), color(1), 8),
                                {{{1, 1, 1}, color(4)}}, color(0.2f), nothing_blocks<T>());
    CHECK_MESSAGE(colour_agrees(c, 0.1L, 0.1L, 0.1L),
                  "a light at distance 0 would divide by zero: it contributes nothing, no infinity, no NaN");
}

TEST_CASE_TEMPLATE("hidden: shade rejects a zero normal or viewer direction", T, RT_SCALARS) {
    int threw = 0;
    try {
        (void)ch06::shade(vec3<T>(0), vec3<T>(0), vec3<T>(0, 1, 0), material{}, {{{0, 2, 0}, color(1)}}, color(0),
                          nothing_blocks<T>());
    } catch (const std::invalid_argument&) {
        ++threw;
    }
    try {
        (void)ch06::shade(vec3<T>(0), vec3<T>(0, 1, 0), vec3<T>(0), material{}, {{{0, 2, 0}, color(1)}}, color(0),
                          nothing_blocks<T>());
    } catch (const std::invalid_argument&) {
        ++threw;
    }
    CHECK_MESSAGE(threw == 2, "bad input is a clear error: a zero normal or to_viewer throws std::invalid_argument");
}

// --- shadow acne in whole pictures ------------------------------------------------

TEST_CASE_TEMPLATE("hidden: no shadow acne in a rendered test scene", T, RT_SCALARS) {
    long lit = 0;
    const long acne = count_acne(make_scene<T>(T(1), vec3<T>(0)), 96, 72, lit);
    CHECK_MESSAGE((lit > 3000 && acne == 0),
                  "shadow acne: in a small rendered scene, shadow rays hit the very surface they leave");
}

TEST_CASE_TEMPLATE("hidden: no shadow acne in a rendered scene far from the origin", T, RT_SCALARS) {
    long lit = 0;
    const long acne = count_acne(make_scene<T>(T(200), vec3<T>(T(3e4), T(1e4), T(-8e4))), 96, 72, lit);
    CHECK_MESSAGE((lit > 3000 && acne == 0),
                  "shadow acne at large coordinates: the offset must grow with the hit point's coordinates");
}

TEST_CASE_TEMPLATE("hidden: no shadow acne in a tiny rendered scene", T, RT_SCALARS) {
    long lit = 0;
    const long acne = count_acne(make_scene<T>(T(1e-3), vec3<T>(0)), 96, 72, lit);
    CHECK_MESSAGE((lit > 3000 && acne == 0), "shadow acne in a millimetre-sized scene");
}

TEST_CASE_TEMPLATE("hidden: small blockers near the surface still cast shadows", T, RT_SCALARS) {
    random_source<T> rnd(614);
    bool ok = true;
    for (int i = 0; i < 200 && ok; ++i) {
        // A tiny ball hovering just above a floor point, the light straight above both.
        const T size = std::exp(rnd.uniform(std::log(T(1e-3)), std::log(T(1))));
        const vec3<T> p(rnd.uniform(-size, size), 0, rnd.uniform(-size, size));
        const sphere<T> ball{p + vec3<T>(0, T(0.05) * size, 0), T(0.01) * size, 0};
        const auto hits_ball = [&](const ray<T>& r, const interval<T>& range) {
            return ch02::intersect_sphere(ball, r, range).has_value();
        };
        const ch06::occlusion_test<T> by_ball = rt::test::served_occlusion<T>{hits_ball};
        const color c = ch06::shade(p, vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), glossy(color(0.5f), color(0), 8),
                                    {{convert<double>(vec3<T>(p + vec3<T>(0, size, 0))), color(1)}}, color(0), by_ball);
        ok = c.r == 0.0f;
    }
    CHECK_MESSAGE(ok, "a small object close above a surface must shadow it: the shadow ray's offset must stay "
                      "far smaller than the scene (a fixed epsilon can step over small blockers)");
}

// Catches: a shade() that drops to ambient as soon as ANY light is blocked
// (`return ambient * diffuse` instead of `continue`), and one that stops at
// the first blocked light (`break`). Every unit test above blocks all lights
// or none, where both mistakes give the right answer.
TEST_CASE_TEMPLATE("hidden: only the blocked lights lose their light", T, RT_SCALARS) {
    random_source<T> rnd(615);
    bool ok = true;
    const material m = glossy(color(0.6f, 0.5f, 0.4f), color(0.3f), 16);
    for (int i = 0; i < 200 && ok; ++i) {
        // The viewer on the normal's side, so shade() keeps the normal as it is.
        const vec3<T> p = rnd.direction(T(0.1), T(5)), n = rnd.direction();
        const vec3<T> v = normalize(n) + rnd.direction(T(0.1), T(0.5));
        std::vector<point_light> lights;
        while (lights.size() < 3) {  // three lights above the surface, so each one counts
            const vec3<T> l = p + rnd.direction(T(1), T(5));
            if (dot(l - p, n) > T(0.2) * length(l - p) * length(n))
                lights.push_back({convert<double>(l), color(2.0f + float(lights.size()), 3.0f, 1.0f)});
        }
        // Block exactly one light: the one whose shadow ray heads for it.
        const size_t blocked = size_t(i % 3);
        const vec3<T> target = convert<T>(lights[blocked].position);
        const auto heads_for_target = [&](const ray<T>& r, const interval<T>& range) {
            const vec3<T> end = r.at(range.max);
            return ld_len(vec3<T>(end - target)) <= 1e-3L * (1 + ld_len(target));
        };
        const ch06::occlusion_test<T> blocks_one = rt::test::served_occlusion<T>{heads_for_target};
        std::vector<point_light> open;
        for (size_t k = 0; k < lights.size(); ++k)
            if (k != blocked) open.push_back(lights[k]);
        const color amb(0.1f);
        const color got = ch06::shade(p, n, v, m, lights, amb, blocks_one);
        const color want = ch06::shade(p, n, v, m, open, amb, nothing_blocks<T>());
        ok = colour_agrees(got, want.r, want.g, want.b) && !colour_agrees(got, 0.06L, 0.05L, 0.04L);
    }
    CHECK_MESSAGE(ok, "each light is shadowed on its own: a blocked light adds nothing, and every other light "
                      "still adds its part (skip the blocked light, do not stop or fall back to ambient)");
}

// Catches: an offset of `offset * normal` without dividing by |normal|, so a
// long normal pushes the origin far off the surface (small blockers are
// missed) and a short one leaves it in the surface (shadow acne). The header
// allows a normal of any length.
TEST_CASE_TEMPLATE("hidden: the shadow offset does not grow or shrink with the normal's length", T, RT_SCALARS) {
    random_source<T> rnd(616);
    bool ok = true;
    for (int i = 0; i < 500 && ok; ++i) {
        const vec3<T> p = rnd.direction(T(1e-1), T(1e3)), to_light = rnd.direction();
        const vec3<T> unit_n = normalize(rnd.direction());
        const T stretch = i % 2 == 0 ? T(1e3) * rnd.uniform(1, 10) : T(1e-3) * rnd.uniform(1, 10);
        const ld moved_unit = ld_len(vec3<T>(ch06::shadow_ray_origin(p, unit_n, to_light) - p));
        const ld moved_long = ld_len(vec3<T>(ch06::shadow_ray_origin(p, unit_n * stretch, to_light) - p));
        ok = moved_unit > 0 && moved_long <= 2 * moved_unit && moved_long >= 0.5L * moved_unit;
    }
    CHECK_MESSAGE(ok, "the normal gives only the direction of the shadow ray's offset: its length must not "
                      "change how far the origin moves");
}
