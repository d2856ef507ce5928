// Hidden tests for chapter 09 (run by the autograder only).
//
// Failure messages name the idea that went wrong, never the inputs or the
// expected numbers: every check is a plain bool computed beforehand. Random
// cases use fixed seeds; the stiff spawn cases are drawn from seeds and
// families the public tests do not use.
#include "09-reflection/optics.hpp"
#include "09-reflection/spawn.hpp"
#include "09-reflection/whitted.hpp"

#include "../public/ch09_cases.hpp"
#include "test_support.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

using namespace rt;
using ld = long double;

namespace {

template <class T>
ld tol() {
    return sizeof(T) == 4 ? 3e-5L : 1e-12L;
}

template <class T>
struct random_source {
    std::mt19937_64 gen;
    explicit random_source(unsigned long long seed) : gen(seed) {}
    T uniform(T lo, T hi) { return T(std::uniform_real_distribution<double>(double(lo), double(hi))(gen)); }
    vec3<T> unit() {
        for (;;) {
            const vec3<T> v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
            const T len2 = dot(v, v);
            if (len2 > T(0.01) && len2 < T(1)) return v / std::sqrt(len2);
        }
    }
    // A direction arriving at a surface with unit normal n (dot < 0), of random length.
    vec3<T> arriving(const vec3<T>& n) {
        vec3<T> d = unit();
        if (dot(d, n) > T(0)) d = -d;
        if (!(dot(d, n) < T(-1e-3))) d = d - n;
        return d * std::exp(uniform(-3, 3));
    }
};

template <class T>
vec3<ld> wide(const vec3<T>& v) {
    return vec3<ld>(ld(v.x), ld(v.y), ld(v.z));
}

template <class T>
bool near(const vec3<T>& got, const vec3<ld>& want, ld scale) {
    const vec3<ld> g = wide(got);
    for (int i = 0; i < 3; ++i)
        if (!(std::isfinite(g[i]) && std::fabs(g[i] - want[i]) <= tol<T>() * 20 * scale)) return false;
    return true;
}

// References in long double, from the same inputs.
template <class T>
vec3<ld> reference_reflect(const vec3<T>& d, const vec3<T>& n) {
    const vec3<ld> D = wide(d), N = wide(n);
    return D - 2 * dot(D, N) * N;
}

template <class T>
std::optional<vec3<ld>> reference_refract(const vec3<T>& d, const vec3<T>& n, T eta) {
    const vec3<ld> u = wide(d) / std::sqrt(dot(wide(d), wide(d))), N = wide(n);
    const ld cos_i = std::min<ld>(1, -dot(u, N));
    const ld e = eta;
    const ld sin2_t = e * e * (1 - cos_i * cos_i);
    if (sin2_t > 1) return std::nullopt;
    return e * u + (e * cos_i - std::sqrt(1 - sin2_t)) * N;
}

ld reference_fresnel(ld cos_i, ld eta) {
    cos_i = std::clamp<ld>(cos_i, 0, 1);
    const ld sin2_t = eta * eta * (1 - cos_i * cos_i);
    if (sin2_t >= 1) return 1;
    const ld cos_t = std::sqrt(1 - sin2_t);
    const ld rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const ld rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (rs * rs + rp * rp) / 2;
}

ld reference_schlick(ld cos_i, ld eta) {
    cos_i = std::clamp<ld>(cos_i, 0, 1);
    const ld r0 = ((1 - eta) / (1 + eta)) * ((1 - eta) / (1 + eta));
    ld c = cos_i;
    if (eta > 1) {
        const ld sin2_t = eta * eta * (1 - cos_i * cos_i);
        if (sin2_t >= 1) return 1;
        c = std::sqrt(1 - sin2_t);
    }
    return r0 + (1 - r0) * std::pow(1 - c, 5);
}

const ld glass_indices[] = {1.33L, 1.5L, 1.7L, 2.42L};

// The mirror direction, the tests' own.
template <class T>
vec3<T> mirror(const vec3<T>& d, const vec3<T>& n) {
    return d - T(2) * dot(d, n) * n;
}

// Held-out stiff cases: other seeds, and families the public tests do not draw.
template <class T>
std::vector<rt::test::spawn_case<T>> held_out_cases() {
    using namespace rt::test::cases_detail;
    std::vector<rt::test::spawn_case<T>> out = rt::test::stiff_spawn_cases<T>(77019, 50);
    rng<T> g(77020);
    add_sphere_cases(out, "ground sphere of radius 1e5, far along", sphere<T>{{T(3e4), T(-1e5), T(-2e4)}, T(1e5), 0},
                     vec3<T>(T(3e4), 5, T(-2e4)), T(2e-2), T(0), 50, g);
    add_sphere_cases(out, "large sphere grazed", sphere<T>{{0, 0, T(-3e3)}, T(1e3), 0}, vec3<T>(0), T(0.9), T(3e-5), 50,
                     g);
    add_triangle_cases(out, "sliver triangle", triangle<T>{{T(-50), 0, T(-20)}, {T(50), T(0.001), T(-20)}, {T(-49.9), T(0.002), T(-20.001)}, 0},
                       vec3<T>(0, 3, 0), T(0), 50, g);
    add_plane_cases(out, "axis plane out to 1e5", plane<T>{{T(0.3), T(0.1), T(0.7)}, {T(0.01), 1, T(-0.02)}, 0}, T(1e5),
                    T(0), 50, g);
    return out;
}

// Scenes for trace, as in the public tests but with other numbers.
template <class T>
scene<T> hall_of_mirrors(float k, float ambient) {
    scene<T> s;
    material m;
    m.diffuse = color(0.5f);
    m.specular = color(0.0f);
    m.mirror = color(k);
    s.materials = {m};
    s.planes = {plane<T>{{0, T(-1), 0}, {0, 1, 0}, 0}, plane<T>{{0, T(2), 0}, {0, -1, 0}, 0}};
    s.ambient = color(ambient);
    s.background = color(0.0f);
    return s;
}

float hall_expected(float k, float local, int depth, float throughput) {
    float sum = local, weight = 1;
    for (int j = 1; j <= depth; ++j) {
        weight *= k;
        if (!(throughput * weight >= ch09::min_throughput)) break;
        sum += local * weight;
    }
    return sum;
}

template <class T>
scene<T> glass_ball(float ior) {
    scene<T> s;
    material glass;
    glass.diffuse = color(0.0f);
    glass.specular = color(0.0f);
    glass.ior = ior;
    s.materials = {glass};
    s.spheres = {sphere<T>{{T(1), T(-2), T(-6)}, T(1.5), 0}};
    s.ambient = color(0.0f);
    s.background = color(0.9f, 0.6f, 0.3f);
    return s;
}

double glass_expected(double f, bool inside, int depth, double throughput) {
    const auto secondary = [&](double w, const std::function<double(int, double)>& next) {
        if (depth == 0 || !(throughput * w >= double(ch09::min_throughput))) return 0.0;
        return w * next(depth - 1, throughput * w);
    };
    const auto background = [](int, double) { return 1.0; };
    const auto again = [f](int d, double t) { return glass_expected(f, true, d, t); };
    if (!inside) return secondary(f, background) + secondary(1 - f, again);
    return secondary(f, again) + secondary(1 - f, background);
}

bool colour_close(const color& got, const color& want, float tol = 3e-4f) {
    for (int i = 0; i < 3; ++i)
        if (!(std::isfinite(got[i]) && std::fabs(got[i] - want[i]) <= tol * (1 + std::fabs(want[i])))) return false;
    return true;
}

}  // namespace

// --- optics ---------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: optics: reflect mirrors random directions about the normal", T, RT_SCALARS) {
    random_source<T> g(9101);
    bool ok = true;
    for (int i = 0; i < 400; ++i) {
        const vec3<T> n = g.unit();
        const vec3<T> d = g.arriving(n);
        ok = ok && near(ch09::reflect(d, n), reference_reflect(d, n), ld(length(d)));
    }
    CHECK_MESSAGE(ok, "reflect is the mirror direction d - 2 (d . n) n");
}

TEST_CASE_TEMPLATE("hidden: optics: a reflected ray leaves on the side it came from", T, RT_SCALARS) {
    random_source<T> g(9102);
    bool ok = true;
    for (int i = 0; i < 400; ++i) {
        const vec3<T> n = g.unit();
        const vec3<T> d = g.arriving(n);
        const vec3<T> r = ch09::reflect(d, n);
        ok = ok && dot(r, n) > T(0) && std::fabs(length(r) - length(d)) <= T(tol<T>() * 10) * length(d);
    }
    CHECK_MESSAGE(ok, "the mirror direction points back to the incident side and keeps the length of d");
}

TEST_CASE_TEMPLATE("hidden: optics: refract matches Snell's law entering and leaving", T, RT_SCALARS) {
    random_source<T> g(9103);
    bool ok = true;
    int compared = 0;
    for (ld index : glass_indices)
        for (const T eta : {T(1 / index), T(index)})
            for (int i = 0; i < 100; ++i) {
                const vec3<T> n = g.unit();
                const vec3<T> d = g.arriving(n);
                const auto want = reference_refract(d, n, eta);
                if (!want) continue;
                // Away from the critical angle, where the answer is well conditioned.
                if (dot(*want, wide(n)) > -0.05L) continue;
                const auto got = ch09::refract(d, n, eta);
                ++compared;
                ok = ok && got.has_value() && near(*got, *want, 1 / -dot(*want, wide(n)));
            }
    CHECK(compared > 300);
    CHECK_MESSAGE(ok, "the refracted direction follows Snell's law with eta = n_incident / n_transmitted");
}

TEST_CASE_TEMPLATE("hidden: optics: total internal reflection only past the critical angle", T, RT_SCALARS) {
    const vec3<T> n(0, 0, 1);
    bool ok = true;
    for (ld index : glass_indices) {
        const ld critical = std::asin(1 / index);
        for (ld step : {-0.05L, -0.01L, 0.01L, 0.05L, 0.3L}) {
            const ld a = critical + step;
            if (!(a < 1.57L)) continue;
            const vec3<T> d(T(std::sin(a)), T(0.0), T(-std::cos(a)));
            const bool tir = step > 0;
            const auto inside = ch09::refract(d, n, T(index));
            ok = ok && inside.has_value() == !tir;
            if (inside) ok = ok && std::isfinite(inside->x) && std::isfinite(inside->z) && inside->z < T(0);
            // From the other side (into the denser medium) there is never total internal reflection.
            ok = ok && ch09::refract(d, n, T(1 / index)).has_value();
        }
    }
    CHECK_MESSAGE(ok, "refract gives no direction exactly when eta^2 (1 - cos_i^2) > 1");
}

TEST_CASE_TEMPLATE("hidden: optics: refracted directions are unit, go through and are never NaN", T, RT_SCALARS) {
    random_source<T> g(9104);
    bool ok = true;
    for (ld index : glass_indices)
        for (const T eta : {T(1 / index), T(index)})
            for (int i = 0; i < 100; ++i) {
                const vec3<T> n = g.unit();
                const vec3<T> d = g.arriving(n);
                const auto t = ch09::refract(d, n, eta);
                if (!t) continue;
                ok = ok && is_finite(*t) && std::fabs(length(*t) - T(1)) <= T(1e-3) && dot(*t, n) <= T(0);
            }
    CHECK_MESSAGE(ok, "a transmitted direction is unit length, crosses the surface and is finite");
}

TEST_CASE_TEMPLATE("hidden: optics: fresnel_dielectric is the exact reflectance", T, RT_SCALARS) {
    random_source<T> g(9105);
    bool ok = true;
    for (ld index : glass_indices)
        for (const T eta : {T(1 / index), T(index)})
            for (int i = 0; i < 200; ++i) {
                const T c = g.uniform(0, 1);
                const ld want = reference_fresnel(ld(c), ld(eta));
                const T got = ch09::fresnel_dielectric(c, eta);
                ok = ok && std::isfinite(got) && std::fabs(ld(got) - want) <= 200 * tol<T>();
            }
    CHECK_MESSAGE(ok, "fresnel_dielectric follows Fresnel's equations (the exact form, averaged over polarisations)");
}

TEST_CASE_TEMPLATE("hidden: optics: fresnel_dielectric is one under total internal reflection", T, RT_SCALARS) {
    bool ok = true;
    for (ld index : glass_indices)
        for (ld c = 0; c < 1; c += 0.01L)
            if (index * index * (1 - c * c) > 1.001L) ok = ok && ch09::fresnel_dielectric(T(c), T(index)) == T(1);
    CHECK_MESSAGE(ok, "under total internal reflection all light is reflected");
}

TEST_CASE_TEMPLATE("hidden: optics: normal incidence reflectance", T, RT_SCALARS) {
    bool ok = true;
    for (ld index : glass_indices) {
        const ld want = ((1 - index) / (1 + index)) * ((1 - index) / (1 + index));
        ok = ok && std::fabs(ld(ch09::fresnel_dielectric(T(1), T(1 / index))) - want) <= 20 * tol<T>();
        ok = ok && std::fabs(ld(ch09::fresnel_dielectric(T(1), T(index))) - want) <= 20 * tol<T>();
        ok = ok && std::fabs(ld(ch09::schlick(T(1), T(index))) - want) <= 20 * tol<T>();
    }
    CHECK_MESSAGE(ok, "at normal incidence both forms reflect ((n1 - n2) / (n1 + n2))^2");
}

TEST_CASE_TEMPLATE("hidden: optics: reflectance is the same from both sides of the interface", T, RT_SCALARS) {
    bool ok = true;
    for (ld index : glass_indices)
        for (ld c = 0.02L; c <= 1; c += 0.02L) {
            const ld sin2_t = (1 - c * c) / (index * index);
            const ld cos_t = std::sqrt(1 - sin2_t);
            const T out = ch09::fresnel_dielectric(T(c), T(1 / index));
            const T in = ch09::fresnel_dielectric(T(cos_t), T(index));
            ok = ok && std::fabs(ld(out) - ld(in)) <= 500 * tol<T>();
        }
    CHECK_MESSAGE(ok, "light crossing an interface either way is reflected by the same fraction");
}

TEST_CASE_TEMPLATE("hidden: optics: schlick is R0 + (1 - R0)(1 - c)^5 with the cosine on the low-index side", T,
                   RT_SCALARS) {
    random_source<T> g(9106);
    bool ok = true;
    for (ld index : glass_indices)
        for (const T eta : {T(1 / index), T(index)})
            for (int i = 0; i < 200; ++i) {
                const T c = g.uniform(0, 1);
                const T got = ch09::schlick(c, eta);
                ok = ok && std::isfinite(got) && std::fabs(ld(got) - reference_schlick(ld(c), ld(eta))) <= 200 * tol<T>();
            }
    CHECK_MESSAGE(ok, "Schlick's approximation, with cos_t inside the denser medium");
}

TEST_CASE_TEMPLATE("hidden: optics: reflectances stay in [0, 1] for any cosine", T, RT_SCALARS) {
    bool ok = true;
    for (ld index : glass_indices)
        for (const T eta : {T(1 / index), T(index)})
            for (T c : {T(-0.5), T(-0.0), T(0), T(1e-30), T(0.5), T(1), T(1.5)}) {
                const T f = ch09::fresnel_dielectric(c, eta), s = ch09::schlick(c, eta);
                ok = ok && f >= T(0) && f <= T(1) && s >= T(0) && s <= T(1);
            }
    CHECK_MESSAGE(ok, "a cosine outside [0, 1] is clamped, and a reflectance is a fraction");
}

// --- spawn ----------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: spawn: the origin moves along the normal only", T, RT_SCALARS) {
    bool ok = true;
    for (const auto& c : held_out_cases<T>()) {
        const vec3<T> w = mirror(c.incoming, c.outward);
        const vec3<T> moved = ch09::offset_ray_origin(c.surface, c.outward, w) - c.surface.point;
        const T along = dot(moved, c.outward);
        const vec3<T> across = moved - along * c.outward;
        const T steps = rt::test::float_steps_along(c.surface.point, vec3<T>(1, 1, 1));
        ok = ok && length(across) <= T(4) * steps + T(1e-3) * std::fabs(along);
    }
    CHECK_MESSAGE(ok, "a spawned ray's origin is pushed along the surface normal, not along the ray");
}

TEST_CASE_TEMPLATE("hidden: spawn: the push is the error bound projected on the normal", T, RT_SCALARS) {
    bool ok = true;
    for (const auto& c : held_out_cases<T>()) {
        const vec3<T> w = mirror(c.incoming, c.outward);
        const T along = dot(ch09::offset_ray_origin(c.surface, c.outward, w) - c.surface.point, c.outward);
        const T reach = rt::test::reach_along(c.surface, c.outward);
        const T steps = rt::test::float_steps_along(c.surface.point, c.outward);
        ok = ok && along >= reach * (T(1) - T(8) * std::numeric_limits<T>::epsilon()) &&
             along <= T(2) * (reach + steps);
    }
    CHECK_MESSAGE(ok, "the origin moves by dot(|n|, error) along the normal, and a float step more");
}

TEST_CASE_TEMPLATE("hidden: spawn: no reflected ray starts inside its surface on held-out stiff cases", T, RT_SCALARS) {
    int wrong = 0;
    for (const auto& c : held_out_cases<T>()) {
        const vec3<T> out = c.outward;
        if (c.side(ch09::offset_ray_origin(c.surface, out, mirror(c.incoming, out))) != 1) ++wrong;
        if (c.side(ch09::offset_ray_origin(c.surface, -out, mirror(-c.incoming, -out))) != -1) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "a reflected ray must start on the side it came from, clear of the surface's error bound");
}

TEST_CASE_TEMPLATE("hidden: spawn: every refracted ray starts on the far side on held-out stiff cases", T, RT_SCALARS) {
    int wrong = 0;
    for (const auto& c : held_out_cases<T>()) {
        const vec3<T> out = c.outward;
        if (c.side(ch09::offset_ray_origin(c.surface, out, c.incoming)) != -1) ++wrong;
        if (c.side(ch09::offset_ray_origin(c.surface, -out, -c.incoming)) != 1) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "a refracted ray must start on the far side of the surface it crosses");
}

TEST_CASE_TEMPLATE("hidden: spawn: no thin shell is skipped on held-out stiff cases", T, RT_SCALARS) {
    int skipped = 0;
    for (const auto& c : held_out_cases<T>()) {
        const vec3<T> n = c.outward;
        const rt::test::quad shell = 2 * (rt::test::quad(rt::test::reach_along(c.surface, n)) +
                                          rt::test::quad(rt::test::float_steps_along(c.surface.point, n)));
        for (const vec3<T>& w : {mirror(c.incoming, n), c.incoming}) {
            const rt::test::quad along = rt::test::quad_dot(ch09::offset_ray_origin(c.surface, n, w) - c.surface.point, n);
            if (!(along < shell && along > -shell)) ++skipped;
        }
    }
    CHECK_MESSAGE(skipped == 0, "the offset must stay within the error bound, or rays skip thin shells");
}

TEST_CASE_TEMPLATE("hidden: spawn: the normal's sign does not change the origin", T, RT_SCALARS) {
    bool ok = true;
    for (const auto& c : held_out_cases<T>())
        for (const vec3<T>& w : {mirror(c.incoming, c.outward), c.incoming})
            ok = ok && ch09::offset_ray_origin(c.surface, c.outward, w) == ch09::offset_ray_origin(c.surface, -c.outward, w);
    CHECK_MESSAGE(ok, "the side of the push is decided by the ray's direction, whichever way the normal points");
}

TEST_CASE_TEMPLATE("hidden: spawn: a push smaller than the rounding still leaves the surface", T, RT_SCALARS) {
    // An error bound far below one ulp of the point: p + s n rounds back to p,
    // and only the final float step moves the origin off the surface.
    const ch09::surface_point<T> p{{T(0.25), T(1), T(-3)}, {T(1e-30), T(1e-30), T(1e-30)}};
    const vec3<T> n(0, 1, 0);
    const vec3<T> up = ch09::offset_ray_origin(p, n, vec3<T>(T(0.3), 1, 0));
    const vec3<T> down = ch09::offset_ray_origin(p, n, vec3<T>(T(0.3), -1, 0));
    CHECK_MESSAGE((up.y > T(1) && down.y < T(1) && up.x == T(0.25) && up.z == T(-3)),
                  "the rounded sum is stepped one float further from the surface, in the components that moved");
}

// --- trace ----------------------------------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: trace: the depth limits the bounces between two mirrors", T, RT_SCALARS) {
    const float k = 0.7f, ambient = 0.3f;
    const scene<T> s = hall_of_mirrors<T>(k, ambient);
    const ray<T> r{{0, T(0.5), 0}, {0, T(-3), 0}};
    bool ok = true;
    for (int depth : {0, 1, 2, 4, 7})
        ok = ok && colour_close(ch09::trace(s, r, rt::test::everything_ahead<T>(), depth, 1.0f),
                                color(hall_expected(k, ambient * 0.5f, depth, 1.0f)));
    CHECK_MESSAGE(ok, "depth N follows exactly N bounces after the first hit");
}

TEST_CASE_TEMPLATE("hidden: trace: faint rays are not traced", T, RT_SCALARS) {
    const float k = 0.4f, ambient = 0.3f;
    const scene<T> s = hall_of_mirrors<T>(k, ambient);
    const ray<T> r{{0, T(0.5), 0}, {0, T(2), 0}};
    bool ok = true;
    for (float throughput : {1.0f, 0.1f, 0.01f})
        ok = ok && colour_close(ch09::trace(s, r, rt::test::everything_ahead<T>(), 30, throughput),
                                color(hall_expected(k, ambient * 0.5f, 30, throughput)), 1e-5f);
    CHECK_MESSAGE(ok, "a ray whose throughput falls below min_throughput is not traced");
}

TEST_CASE_TEMPLATE("hidden: trace: glass splits light by Fresnel at each face", T, RT_SCALARS) {
    bool ok = true;
    for (float ior : {1.33f, 2.0f}) {
        const scene<T> s = glass_ball<T>(ior);
        const ray<T> r{{T(1), T(-2), T(0)}, {0, 0, T(-0.5)}};  // through the centre
        const double f = double(((1 - ld(ior)) / (1 + ld(ior))) * ((1 - ld(ior)) / (1 + ld(ior))));
        for (int depth : {1, 2, 5}) {
            const double want = glass_expected(f, false, depth, 1.0);
            ok = ok && colour_close(ch09::trace(s, r, rt::test::everything_ahead<T>(), depth, 1.0f),
                                    s.background * float(want));
        }
    }
    CHECK_MESSAGE(ok, "glass reflects F and transmits 1 - F at every face, entering and leaving");
}

TEST_CASE_TEMPLATE("hidden: trace: light inside glass past the critical angle is trapped", T, RT_SCALARS) {
    // A ray inside a glass ball meeting its surface at 50 degrees: past the
    // critical angle of index 1.5 (41.8 degrees), and by symmetry at every
    // later bounce too. All of it stays inside; nothing of the background
    // is seen.
    const scene<T> s = glass_ball<T>(1.5f);
    const vec3<T> c = s.spheres[0].center;
    const T rad = s.spheres[0].radius;
    const ld a = 50 * 3.14159265358979323846L / 180;
    // From a point on the chord at distance rad sin(a) from the centre, along the chord.
    const vec3<T> origin = c + vec3<T>(T(rad * std::sin(a)), 0, 0);
    const ray<T> r{origin, {0, 0, 1}};
    const color got = ch09::trace(s, r, rt::test::everything_ahead<T>(), 6, 1.0f);
    CHECK_MESSAGE(colour_close(got, color(0.0f), 1e-5f),
                  "leaving glass the ratio is ior / 1, and past the critical angle light is totally reflected");
}

TEST_CASE_TEMPLATE("hidden: trace: a mirror adds its tinted reflection", T, RT_SCALARS) {
    scene<T> s;
    material shiny, matte;
    shiny.diffuse = color(0.2f, 0.1f, 0.05f);
    shiny.specular = color(0.3f);
    shiny.shininess = 50;
    shiny.mirror = color(0.3f, 0.6f, 0.9f);
    matte.diffuse = color(0.4f, 0.8f, 0.3f);
    matte.specular = color(0.0f);
    s.materials = {shiny, matte};
    s.spheres = {sphere<T>{{T(0.3), 0, -6}, T(1.2), 0}, sphere<T>{{0, 0, 6}, 2, 1}};
    s.lights = {point_light{{-2, 4, 1}, color(30.0f)}};
    s.ambient = color(0.07f);
    s.background = color(0.1f, 0.2f, 0.3f);
    bool ok = true;
    for (T y : {T(-0.01), T(0.0), T(0.03)}) {
        const ray<T> r{{0, y, 0}, {0, 0, T(-2)}};
        const auto h = ch09::closest_surface_hit(s, r, rt::test::everything_ahead<T>());
        if (!h) {
            ok = false;
            continue;
        }
        const vec3<T> n = h->facing_normal();
        const ray<T> bounce = ch09::spawn_ray(h->surface, n, mirror(r.direction, n));
        const auto seen = ch09::closest_surface_hit(s, bounce, rt::test::everything_ahead<T>());
        const color behind = seen ? ch09::local_light(s, *seen, bounce) : s.background;
        const color want = ch09::local_light(s, *h, r) + shiny.mirror * behind;
        ok = ok && colour_close(ch09::trace(s, r, rt::test::everything_ahead<T>(), 1, 1.0f), want);
    }
    CHECK_MESSAGE(ok, "a mirror's colour is its local light plus its mirror colour times what the reflected ray sees");
}

TEST_CASE_TEMPLATE("hidden: trace: misses, bad depths and no NaN", T, RT_SCALARS) {
    const scene<T> s = glass_ball<T>(1.5f);
    bool ok = colour_close(ch09::trace(s, ray<T>{{0, 0, 0}, {0, 1, 0}}, rt::test::everything_ahead<T>(), 3, 1.0f),
                           s.background);
    bool refused = false;
    try {
        (void)ch09::trace(s, ray<T>{{0, 0, 0}, {0, 0, -1}}, rt::test::everything_ahead<T>(), -2, 1.0f);
    } catch (const std::invalid_argument&) {
        refused = true;
    }
    // Grazing rays at the ball's rim: finite and not negative.
    for (T x = T(-0.52); x <= T(2.52); x += T(0.01)) {
        const color c = ch09::trace(s, ray<T>{{x, T(-2), 0}, {0, 0, -1}}, rt::test::everything_ahead<T>(), 4, 1.0f);
        ok = ok && std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0 && c.g >= 0 && c.b >= 0;
    }
    CHECK_MESSAGE(ok, "a miss sees the background, and no colour is NaN or negative");
    CHECK_MESSAGE(refused, "a negative depth is refused with std::invalid_argument");
}
