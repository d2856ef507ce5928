// Hidden tests for chapter 07, step 6: the whole robust test (run by the autograder only; steps 1 to 5 on
// their own are in ch07_steps_hidden_test.cpp).
//
// Stiff cases in families, each generated from a fixed seed, in both
// precisions. The reference for every case is computed in long double from
// the very inputs the routine sees (already rounded to T), so a case measures
// the formula, not the rounding of the scene description. Bounds, per family:
//   far spheres (1e2..1e6 radii)        near root within 8 ULPs of T
//   huge ground (1e3..1e6, 1e-2..1 up)  t within 64 ULPs for hits closer than
//                                        8 heights (the foot of the perpendicular
//                                        is radius-sized there, rounded to T, so
//                                        shallow rays lose a few dozen ULPs);
//                                        every downward ray well
//                                        below the horizon hits, every upward ray misses
//   grazing (2..16 ULPs from tangency)  hit/miss exactly right; t within
//                                        R * sqrt(64 eps) (a tangent root is ill-conditioned)
//   tiny and huge radii (1e-4, 1e4)     as random rays, scaled
//   random rays near the sphere         hit/miss right away from tangency; t within 16 ULPs,
//                                        or near the silhouette 16 eps (|f| + r) / sqrt(1 - (l/r)^2)
// Failure messages name the idea that went wrong, never the expected numbers:
// every check is a plain bool computed beforehand.
#include "07-precision/robust_sphere.hpp"

#include "common/error_metrics.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace rt;
using rt::ch07::intersect_sphere_robust;

namespace {

using wide = long double;

template <class T>
T eps() {
    return std::numeric_limits<T>::epsilon();
}

// The exact answer for the T inputs, in long double: perpendicular-foot
// discriminant, c with exact squares (fmal), the stable root pair.
struct reference {
    bool real = false;
    wide t0 = 0, t1 = 0;  // t0 <= t1
    wide l_over_r = 0;    // distance of the line from the centre, in radii
};

template <class T>
reference exact_roots(const sphere<T>& s, const ray<T>& r) {
    reference ref;
    const wide fx = wide(r.origin.x) - wide(s.center.x), fy = wide(r.origin.y) - wide(s.center.y),
               fz = wide(r.origin.z) - wide(s.center.z);
    // What the long double subtraction lost (two-sum): o - C of two doubles
    // can need more than long double's 64 bits, and c needs all of them.
    const auto lost = [](wide o, wide C, wide f) {
        const wide bp = f - o;
        return (o - (f - bp)) + (-C - bp);
    };
    const wide lx = lost(r.origin.x, s.center.x, fx), ly = lost(r.origin.y, s.center.y, fy),
               lz = lost(r.origin.z, s.center.z, fz);
    const wide dx = r.direction.x, dy = r.direction.y, dz = r.direction.z, R = s.radius;
    const wide a = dx * dx + dy * dy + dz * dz;
    const wide hb = fx * dx + fy * dy + fz * dz;
    const wide k = hb / a;
    const wide px = fx - k * dx, py = fy - k * dy, pz = fz - k * dz;
    const wide l2 = px * px + py * py + pz * pz;
    ref.l_over_r = std::sqrt(l2) / R;
    const wide disc = a * (R - std::sqrt(l2)) * (R + std::sqrt(l2));
    if (!(disc >= 0)) return ref;
    // c = f.f - R^2 with each square split exactly into hi + lo.
    wide hi[4] = {fx * fx, fy * fy, fz * fz, -(R * R)};
    wide lo[4] = {std::fma(fx, fx, -hi[0]), std::fma(fy, fy, -hi[1]), std::fma(fz, fz, -hi[2]),
                  -std::fma(R, R, hi[3])};
    wide sum = 0, err = 0;
    for (int i = 0; i < 4; ++i) {
        const wide t = sum + hi[i];
        const wide bp = t - sum;
        err += (sum - (t - bp)) + (hi[i] - bp) + lo[i];
        sum = t;
    }
    const wide c = sum + (err + 2 * (fx * lx + fy * ly + fz * lz));
    const wide q = -(hb + std::copysign(std::sqrt(disc), hb));
    wide x0 = q == 0 ? 0 : c / q, x1 = q / a;
    ref.real = true;
    ref.t0 = std::min(x0, x1);
    ref.t1 = std::max(x0, x1);
    return ref;
}

// The hit the contract asks for, from the reference roots.
std::optional<wide> expected_t(const reference& ref, wide tmin, wide tmax) {
    if (!ref.real) return std::nullopt;
    if (tmin < ref.t0 && ref.t0 < tmax) return ref.t0;
    if (tmin < ref.t1 && ref.t1 < tmax) return ref.t1;
    return std::nullopt;
}

template <class T>
double ulps(T got, wide want) {
    return ulp_distance(got, static_cast<T>(want));
}

// A unit vector in T, uniformly distributed.
template <class T>
vec3<T> random_direction(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    vec3d v;
    do v = vec3d(n(rng), n(rng), n(rng));
    while (!(length(v) > 1e-3));
    return convert<T>(normalize(v));
}

// Any unit vector perpendicular to u.
vec3d perpendicular(const vec3d& u, std::mt19937_64& rng) {
    vec3d v;
    do v = cross(u, convert<double>(random_direction<double>(rng)));
    while (!(length(v) > 1e-3));
    return normalize(v);
}

// A ray from a random point near the sphere towards a random point of its
// disc (so about three quarters of them pass through it), forwards or backwards.
template <class T>
ray<T> aimed_at(const sphere<T>& s, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> coord(-6, 6), spread(0, 1.2);
    const vec3d origin(coord(rng), coord(rng), coord(rng));
    const vec3d target = convert<double>(s.center) + convert<double>(random_direction<T>(rng)) *
                                                        (spread(rng) * double(s.radius));
    const double sign = std::uniform_int_distribution<int>(0, 1)(rng) ? 1 : -1;
    return {convert<T>(origin), convert<T>((target - origin) * sign)};
}

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

// Rounds v to the nearest value whose sum with `base` is exactly representable
// in T, so that a height above a huge sphere is exactly what the inputs say.
template <class T>
T snap_to_spacing_of(T base, T v) {
    return (base + v) - base;
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: far spheres from 1e2 to 1e6 radii keep hit and miss", T, RT_SCALARS) {
    std::mt19937_64 rng(7001);
    std::uniform_real_distribution<double> log_dist(2, 6), offset(0, 2), log_radius(-2, 2);
    int wrong = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const double R = std::pow(10.0, log_radius(rng)), D = R * std::pow(10.0, log_dist(rng));
        const vec3d u = convert<double>(random_direction<T>(rng));
        const vec3d side = perpendicular(u, rng);
        const sphere<T> s{convert<T>(u * D), T(R)};
        const ray<T> r{{0, 0, 0}, convert<T>(u * D + side * (offset(rng) * R))};
        const reference ref = exact_roots(s, r);
        // Position is only known to a few ULPs of the distance: judge rays
        // clearly inside or outside that uncertainty.
        const double margin = 16 * double(eps<T>()) * D / R;
        if (std::fabs(double(ref.l_over_r) - 1) < margin + 1e-6) continue;
        ++checked;
        const bool want = bool(expected_t(ref, 0, infinity<wide>));
        if (intersect_sphere_robust(s, r, ahead<T>()).has_value() != want) ++wrong;
    }
    const bool enough = checked > 1000;
    CHECK_MESSAGE(enough, "far spheres: the test generated too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "far spheres: a sphere thousands of radii away was missed by a ray through it, or hit by a ray "
                      "beside it (is the discriminant computed from the foot of the perpendicular?)");
}

TEST_CASE_TEMPLATE("hidden: far spheres from 1e2 to 1e6 radii give t to a few ULPs", T, RT_SCALARS) {
    std::mt19937_64 rng(7002);
    std::uniform_real_distribution<double> log_dist(2, 6), offset(0, 0.9), log_radius(-2, 2);
    double worst = 0;
    int misses = 0;
    for (int i = 0; i < 3000; ++i) {
        const double R = std::pow(10.0, log_radius(rng)), D = R * std::pow(10.0, log_dist(rng));
        const vec3d u = convert<double>(random_direction<T>(rng));
        const vec3d side = perpendicular(u, rng);
        const sphere<T> s{convert<T>(u * D), T(R)};
        const double scale = std::uniform_real_distribution<double>(0.5, 3)(rng);  // d need not be unit length
        const ray<T> r{{0, 0, 0}, convert<T>((u * D + side * (offset(rng) * R)) * (scale / D))};
        const reference ref = exact_roots(s, r);
        if (ref.l_over_r > wide(0.95)) continue;
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (!got) {
            ++misses;
            continue;
        }
        worst = std::max(worst, ulps(got->t, ref.t0));
    }
    const bool hit_all = misses == 0;
    CHECK_MESSAGE(hit_all, "far spheres: a ray through the middle of a far sphere was reported as a miss");
    const bool ok = worst <= 8;
    CHECK_MESSAGE(ok, "far spheres: the near root is off by more than a few ULPs (cancellation in the near root, "
                      "or the foot of the perpendicular without dividing by d.d?)");
}

TEST_CASE_TEMPLATE("hidden: huge ground spheres give t to a few ULPs from close above", T, RT_SCALARS) {
    std::mt19937_64 rng(7003);
    std::uniform_real_distribution<double> log_r(3, 6), log_h(-2, 0), steep(0.125, 1), turn(0, 6.283185307179586);
    double worst = 0;
    int misses = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const T R = T(std::pow(10.0, log_r(rng)));
        const T h = snap_to_spacing_of(R, T(std::pow(10.0, log_h(rng))));
        if (!(h > T(0))) continue;
        // Centre straight below the origin; the height above the top is exactly h.
        const sphere<T> s{{0, -R, 0}, R};
        const ray<T> r{{0, h, 0}, convert<T>(vec3d(std::cos(turn(rng)), -steep(rng), std::sin(turn(rng))))};
        const reference ref = exact_roots(s, r);
        if (!ref.real || !(ref.t0 * std::sqrt(wide(dot(r.direction, r.direction))) < 8 * wide(h))) continue;
        ++checked;
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (!got) {
            ++misses;
            continue;
        }
        worst = std::max(worst, ulps(got->t, ref.t0));
    }
    const bool enough = checked > 1000;
    CHECK_MESSAGE(enough, "huge ground: the test generated too few cases (a test problem, not yours)");
    const bool hit_all = misses == 0;
    CHECK_MESSAGE(hit_all, "huge ground: a ray pointing down at a huge sphere from close above missed it");
    const bool ok = worst <= 64;
    CHECK_MESSAGE(ok, "huge ground: t of a huge sphere seen from close above is off by more than a few ULPs "
                      "(catastrophic cancellation in the near root, or in c = f.f - r^2?)");
}

TEST_CASE_TEMPLATE("hidden: huge ground spheres are hit below the horizon and missed above it", T, RT_SCALARS) {
    std::mt19937_64 rng(7004);
    std::uniform_real_distribution<double> log_r(3, 6), log_h(-2, 0), turn(0, 6.283185307179586), slope(0.02, 1);
    int wrong = 0;
    for (int i = 0; i < 2000; ++i) {
        const T R = T(std::pow(10.0, log_r(rng)));
        const T h = snap_to_spacing_of(R, T(std::pow(10.0, log_h(rng))));
        if (!(h > T(0))) continue;
        const sphere<T> s{{0, -R, 0}, R};
        // The horizon dips by about sqrt(2h / R) radians: stay 2x away from it.
        const double dip = std::sqrt(2 * double(h) / double(R));
        const double down = -(2 * dip + slope(rng)), up = slope(rng);
        const double a = turn(rng);
        const ray<T> below{{0, h, 0}, convert<T>(vec3d(std::cos(a), down, std::sin(a)))};
        const ray<T> above{{0, h, 0}, convert<T>(vec3d(std::cos(a), up, std::sin(a)))};
        if (!intersect_sphere_robust(s, below, ahead<T>()).has_value()) ++wrong;
        if (intersect_sphere_robust(s, above, ahead<T>()).has_value()) ++wrong;
    }
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "huge ground: a ray below the horizon missed the ground, or a ray above it hit "
                      "(is c = f.f - r^2 accurate? Its sign says whether the origin is outside)");
}

TEST_CASE_TEMPLATE("hidden: grazing rays a few ULPs from tangency are classified exactly", T, RT_SCALARS) {
    std::mt19937_64 rng(7005);
    std::uniform_real_distribution<double> log_radius(-3, 3), distance(2, 10);
    std::uniform_int_distribution<int> steps(2, 16), axis(0, 2), coin(0, 1);
    int wrong = 0, bad_t = 0;
    for (int i = 0; i < 3000; ++i) {
        const T R = T(std::pow(10.0, log_radius(rng)));
        const T D = T(distance(rng)) * R;
        // Offset y = R moved a few representable steps in or out: the ray runs
        // along an axis, so the foot of the perpendicular is exactly y.
        const bool inside = coin(rng) == 1;
        T y = R;
        for (int k = steps(rng); k > 0; --k) y = std::nextafter(y, inside ? T(0) : infinity<T>);
        const int ax = axis(rng), up = (ax + 1) % 3;
        const T sign = coin(rng) ? T(1) : T(-1);
        vec3<T> centre(0), origin(0), dir(0);
        centre[ax] = sign * D;
        origin[up] = y;
        dir[ax] = sign;
        const sphere<T> s{centre, R};
        const ray<T> r{origin, dir};
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (got.has_value() != inside) {
            ++wrong;
            continue;
        }
        if (got) {
            const reference ref = exact_roots(s, r);
            const wide tol = wide(R) * std::sqrt(64 * wide(eps<T>())) + 4 * wide(D) * wide(eps<T>());
            if (!(std::fabs(wide(got->t) - ref.t0) <= tol)) ++bad_t;
        }
    }
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "grazing rays: a ray a few ULPs inside a sphere's silhouette missed, or one a few ULPs "
                      "outside hit (a tangent or near-tangent discriminant must keep its sign)");
    const bool t_ok = bad_t == 0;
    CHECK_MESSAGE(t_ok, "grazing rays: the hit of a near-tangent ray is too far from the sphere");
}

TEST_CASE_TEMPLATE("hidden: the nearer root is returned whatever the sign of half_b", T, RT_SCALARS) {
    std::mt19937_64 rng(7006);
    std::uniform_real_distribution<double> coord(-6, 6), radius(0.5, 2);
    int wrong = 0, checked = 0;
    const wide line_min = -infinity<wide>, line_max = infinity<wide>;
    for (int i = 0; i < 3000; ++i) {
        const sphere<T> s{{T(coord(rng)), T(coord(rng)), T(coord(rng))}, T(radius(rng))};
        const ray<T> r = aimed_at(s, rng);
        const reference ref = exact_roots(s, r);
        if (!ref.real || ref.l_over_r > wide(0.99)) continue;
        ++checked;
        auto got = intersect_sphere_robust(s, r, interval<T>{-infinity<T>, infinity<T>});
        auto want = expected_t(ref, line_min, line_max);
        if (!got || !(ulps(got->t, *want) <= 64 || std::fabs(wide(got->t) - *want) <= 1e-4L * wide(s.radius)))
            ++wrong;
    }
    const bool enough = checked > 500;
    CHECK_MESSAGE(enough, "root order: the test generated too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "root order: with the whole line as range, the smaller root must come back; c / q is the "
                      "far root when half_b > 0");
}

TEST_CASE_TEMPLATE("hidden: tmin and tmax cut between the two roots", T, RT_SCALARS) {
    std::mt19937_64 rng(7007);
    std::uniform_real_distribution<double> coord(-6, 6), radius(0.5, 2), frac(0.1, 0.9);
    int wrong = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const sphere<T> s{{T(coord(rng)), T(coord(rng)), T(coord(rng))}, T(radius(rng))};
        const ray<T> r = aimed_at(s, rng);
        const reference ref = exact_roots(s, r);
        if (!ref.real || ref.l_over_r > wide(0.9)) continue;
        ++checked;
        // A cut strictly between the roots, then ranges on either side of it.
        const wide gap = ref.t1 - ref.t0;
        const T cut = T(ref.t0 + wide(frac(rng)) * gap);
        const T before = T(ref.t0 - gap), after = T(ref.t1 + gap);
        auto only_far = intersect_sphere_robust(s, r, interval<T>{cut, after});
        auto only_near = intersect_sphere_robust(s, r, interval<T>{before, cut});
        auto none = intersect_sphere_robust(s, r, interval<T>{after, infinity<T>});
        auto none_before = intersect_sphere_robust(s, r, interval<T>{-infinity<T>, before});
        const wide tol = 1e-3L * wide(s.radius);
        const bool good = only_far && std::fabs(wide(only_far->t) - ref.t1) <= tol && only_near &&
                          std::fabs(wide(only_near->t) - ref.t0) <= tol && !none && !none_before;
        if (!good) ++wrong;
    }
    const bool enough = checked > 500;
    CHECK_MESSAGE(enough, "interval: the test generated too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "interval: a root outside (tmin, tmax) was returned, or the root inside it was not; check "
                      "both roots of the stable pair against both ends of the range");
}

TEST_CASE_TEMPLATE("hidden: an origin exactly on the surface", T, RT_SCALARS) {
    std::mt19937_64 rng(7008);
    std::uniform_int_distribution<int> small(-64, 64), axis(0, 2), coin(0, 1);
    std::uniform_int_distribution<int> rad(1, 64);
    int wrong = 0;
    for (int i = 0; i < 1000; ++i) {
        // Integer centres and radii: centre + radius along an axis is exact.
        const vec3<T> centre(T(small(rng)), T(small(rng)), T(small(rng)));
        const T R = T(rad(rng));
        const int ax = axis(rng);
        const T sign = coin(rng) ? T(1) : T(-1);
        vec3<T> origin = centre;
        origin[ax] += sign * R;
        vec3<T> out(0);
        out[ax] = sign;
        const sphere<T> s{centre, R};
        const bool leaves = !intersect_sphere_robust(s, ray<T>{origin, out}, ahead<T>()).has_value();
        auto across = intersect_sphere_robust(s, ray<T>{origin, -out}, ahead<T>());
        const bool crosses = across && std::fabs(across->t - 2 * R) <= 4 * R * eps<T>();
        if (!leaves || !crosses) ++wrong;
    }
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "origin on the surface: leaving outwards must not hit t = 0 (not > tmin), and going inwards "
                      "must reach the far side at t = 2R");
}

TEST_CASE_TEMPLATE("hidden: tiny and huge radii behave like unit spheres", T, RT_SCALARS) {
    std::mt19937_64 rng(7009);
    std::uniform_real_distribution<double> coord(-4, 4), radius(0.5, 2);
    int wrong = 0, checked = 0;
    double worst = 0;
    for (double scale : {1e-4, 1e4}) {
        for (int i = 0; i < 1500; ++i) {
            const sphere<T> s{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * scale), T(radius(rng) * scale)};
            const ray<T> r{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * scale), random_direction<T>(rng)};
            const reference ref = exact_roots(s, r);
            if (std::fabs(ref.l_over_r - 1) < 1e-3L) continue;
            auto want = expected_t(ref, 0, infinity<wide>);
            if (want && *want < 1e-3L * wide(s.radius)) continue;  // a root at the origin: too close to tmin to judge
            ++checked;
            auto got = intersect_sphere_robust(s, r, ahead<T>());
            if (got.has_value() != want.has_value()) ++wrong;
            else if (got) worst = std::max(worst, ulps(got->t, *want));
        }
    }
    const bool enough = checked > 1500;
    CHECK_MESSAGE(enough, "scaled spheres: the test generated too few cases (a test problem, not yours)");
    const bool ok = wrong == 0 && worst <= 64;
    CHECK_MESSAGE(ok, "scaled spheres: a sphere of radius 1e-4 or 1e4 was hit, missed or placed differently from "
                      "the same scene at unit scale (no absolute epsilons: every test must scale with the radius)");
}

TEST_CASE_TEMPLATE("hidden: random rays near a sphere agree with the long double answer", T, RT_SCALARS) {
    std::mt19937_64 rng(7010);
    std::uniform_real_distribution<double> coord(-5, 5), radius(0.25, 3), len(0.1, 10);
    int wrong = 0, checked = 0, bad_t = 0;
    for (int i = 0; i < 4000; ++i) {
        const sphere<T> s{{T(coord(rng)), T(coord(rng)), T(coord(rng))}, T(radius(rng))};
        const ray<T> r{{T(coord(rng)), T(coord(rng)), T(coord(rng))},
                       random_direction<T>(rng) * T(len(rng))};
        const reference ref = exact_roots(s, r);
        if (std::fabs(ref.l_over_r - 1) < 1e-3L) continue;  // too close to tangent to judge
        auto want = expected_t(ref, 0, infinity<wide>);
        const wide d_len = std::sqrt(wide(dot(r.direction, r.direction)));
        if (want && *want * d_len < 1e-3L) continue;
        ++checked;
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (got.has_value() != want.has_value()) {
            ++wrong;
        } else if (got) {
            // A few ULPs, or, near the silhouette where a root is sensitive,
            // a distance error a few ULPs of the scene's size times the
            // condition number 1 / sqrt(1 - (l/r)^2) of the root.
            const wide size = wide(length(convert<double>(r.origin) - convert<double>(s.center))) + wide(s.radius);
            const wide kappa = 1 / std::sqrt(std::fabs(1 - ref.l_over_r * ref.l_over_r));
            const bool close_enough = ulps(got->t, *want) <= 16 ||
                                      std::fabs(wide(got->t) - *want) * d_len <= 16 * wide(eps<T>()) * size * kappa;
            if (!close_enough) ++bad_t;
        }
    }
    const bool enough = checked > 3000;
    CHECK_MESSAGE(enough, "random rays: the test generated too few cases (a test problem, not yours)");
    const bool ok_hits = wrong == 0;
    CHECK_MESSAGE(ok_hits, "random rays: some hits were reported as misses or misses as hits");
    const bool ok_t = bad_t == 0;
    CHECK_MESSAGE(ok_t, "random rays: some hits are off by more than a few ULPs (which root? stable pair?)");
}

TEST_CASE_TEMPLATE("hidden: the hit record holds the point and the outward unit normal", T, RT_SCALARS) {
    std::mt19937_64 rng(7011);
    std::uniform_real_distribution<double> coord(-5, 5), radius(0.25, 3), log_dist(0, 4);
    int wrong = 0, hits = 0;
    for (int i = 0; i < 3000; ++i) {
        const T R = T(radius(rng));
        const vec3d u = convert<double>(random_direction<T>(rng));
        const sphere<T> s{convert<T>(u * (double(R) * std::pow(10.0, log_dist(rng)))), R};
        const vec3<T> origin(T(coord(rng)), T(coord(rng)), T(coord(rng)));
        const ray<T> r{origin, convert<T>(convert<double>(s.center) - convert<double>(origin) +
                                          convert<double>(random_direction<T>(rng)) * (0.5 * double(R)))};
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (!got) continue;
        ++hits;
        const vec3<T> p = r.at(got->t);
        const bool point_ok = p == got->point;
        const bool unit = std::fabs(length(got->normal) - T(1)) <= 8 * eps<T>();
        // Outward: the normal agrees with the direction from the centre to the
        // hit, to within the position's uncertainty at this distance.
        const vec3d radial = normalize(convert<double>(got->point) - convert<double>(s.center));
        const double slack = 1e3 * double(eps<T>()) * (length(convert<double>(s.center) - convert<double>(origin)) /
                                                        double(R) + 1);
        const bool outward = dot(convert<double>(got->normal), radial) >= 1 - std::min(0.5, slack);
        const bool object_ok = got->object == -1;
        if (!(point_ok && unit && outward && object_ok)) ++wrong;
    }
    const bool enough = hits > 2000;
    CHECK_MESSAGE(enough, "hit record: the test generated too few hits (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "hit record: point must be r.at(t), normal the outward unit normal, object -1");
}

TEST_CASE_TEMPLATE("hidden: bad input is a miss never a NaN", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
    const sphere<T> s{{0, 0, -4}, T(1)};
    const ray<T> good{{0, 0, 0}, {0, 0, -1}};
    bool ok = !intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, 0}}, ahead<T>()) &&
              !intersect_sphere_robust(s, ray<T>{{0, nan, 0}, {0, 0, -1}}, ahead<T>()) &&
              !intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {nan, 0, -1}}, ahead<T>()) &&
              !intersect_sphere_robust(s, ray<T>{{0, 0, 0}, {0, 0, -inf}}, ahead<T>()) &&
              !intersect_sphere_robust(s, ray<T>{{inf, 0, 0}, {0, 0, -1}}, ahead<T>()) &&
              !intersect_sphere_robust(sphere<T>{{0, 0, -4}, nan}, good, ahead<T>()) &&
              !intersect_sphere_robust(sphere<T>{{0, nan, -4}, T(1)}, good, ahead<T>()) &&
              !intersect_sphere_robust(sphere<T>{{0, 0, -4}, T(0)}, good, ahead<T>()) &&
              !intersect_sphere_robust(sphere<T>{{0, 0, -4}, T(-2)}, good, ahead<T>()) &&
              !intersect_sphere_robust(s, good, interval<T>{nan, inf}) &&
              !intersect_sphere_robust(s, good, interval<T>{0, nan});
    CHECK_MESSAGE(ok, "bad input (zero or infinite direction, NaN anywhere, radius not positive, NaN range) must be "
                      "a miss, never a NaN hit");
}

// Cases the tests above do not build: half_b exactly 0, off-axis huge spheres, the format's limits, secondary rays.

TEST_CASE_TEMPLATE("hidden: half_b exactly 0 (from the centre, or from inside at right angles)", T, RT_SCALARS) {
    // Centre (10, -20, 30), radius 2.5; |(3, 4, 0)| = 5, so from the centre t = 2.5 / 5 = 0.5 both ways.
    const sphere<T> s{{10, -20, 30}, T(2.5)};
    auto from_centre = intersect_sphere_robust(s, ray<T>{{10, -20, 30}, {3, 4, 0}}, ahead<T>());
    const bool centre_ok = from_centre && from_centre->t == T(0.5);
    CHECK_MESSAGE(centre_ok, "from the centre half_b = f.d = 0: q = -(0 + sqrt(disc/4)) is not 0 (only a tangent makes "
                             "it 0), and the roots c / q, q / a are -t and +t; the hit is the positive one");
    // 1.5 off the centre along y, moving along (4, 0, 3): half_b = 0 again, t = sqrt(2.5^2 - 1.5^2) / 5 = 0.4.
    auto sideways = intersect_sphere_robust(s, ray<T>{{10, T(-18.5), 30}, {4, 0, 3}}, ahead<T>());
    const bool side_ok = sideways && ulps(sideways->t, wide(0.4L)) <= 1;
    CHECK_MESSAGE(side_ok, "from inside, at right angles to the radius, half_b = 0 and the roots are +-0.4; a special "
                           "case for half_b == 0 (or a sign(half_b) that is 0) loses this hit");
    // And the same with the range (-inf, inf): the smaller root, -0.4.
    auto both = intersect_sphere_robust(s, ray<T>{{10, T(-18.5), 30}, {4, 0, 3}},
                                        interval<T>{-infinity<T>, infinity<T>});
    const bool both_ok = both && ulps(both->t, wide(-0.4L)) <= 1;
    CHECK_MESSAGE(both_ok, "with half_b = 0 and the whole line as range, the smaller root -0.4 is the answer");
}

TEST_CASE_TEMPLATE("hidden: huge spheres whose centre is off every axis, seen from close above", T, RT_SCALARS) {
    // The centre lies along a general direction from the origin, so every
    // coordinate of f = o - C is huge and cancels in c: a c that is careful
    // with one coordinate only is caught here.
    std::mt19937_64 rng(7011);
    std::uniform_real_distribution<double> height(0.01, 1), angle(-1.4, 0.1), spin(0, 6.283185307179586);
    int wrong = 0, bad_t = 0, checked = 0;
    for (double R : {1e4, 1e6}) {
        for (int i = 0; i < 400; ++i) {
            const vec3d up = convert<double>(random_direction<double>(rng));
            const vec3d u = perpendicular(up, rng), v = cross(up, u);
            const double h = height(rng), el = angle(rng), az = spin(rng);
            const sphere<T> s{convert<T>(up * -(R + h)), T(R)};
            const vec3d dir = std::sin(el) * up + std::cos(el) * (std::cos(az) * u + std::sin(az) * v);
            const ray<T> r{{0, 0, 0}, convert<T>(dir)};
            const reference ref = exact_roots(s, r);
            if (std::fabs(ref.l_over_r - 1) < 1e-6L) continue;  // the horizon: too sensitive to judge
            auto want = expected_t(ref, 0, infinity<wide>);
            ++checked;
            auto got = intersect_sphere_robust(s, r, ahead<T>());
            if (got.has_value() != want.has_value()) ++wrong;
            else if (got && want && *want < 8 * h && ulps(got->t, *want) > 4) ++bad_t;
        }
    }
    CHECK_MESSAGE(checked > 600, "off-axis ground: too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "off-axis huge spheres: hits and misses below and above the horizon were confused");
    const bool ok_t = bad_t == 0;
    CHECK_MESSAGE(ok_t, "off-axis huge spheres: t is off by more than 4 ULPs; with the centre off the axes all three "
                        "squares of f.f - r^2 cancel together (keep every low half), and f = o - C must be exact");
}

TEST_CASE_TEMPLATE("hidden: spheres at the limits of the format, and subnormal directions", T, RT_SCALARS) {
    std::mt19937_64 rng(7012);
    std::uniform_real_distribution<double> coord(-4, 4), radius(0.5, 2);
    const std::vector<double> scales = sizeof(T) == sizeof(float) ? std::vector<double>{1e-30, 1e-34, 1e30, 1e34}
                                                                  : std::vector<double>{1e-200, 1e-290, 1e200, 1e290};
    int wrong = 0, bad_t = 0, checked = 0;
    for (double scale : scales) {
        for (int i = 0; i < 300; ++i) {
            const sphere<T> s{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * scale), T(radius(rng) * scale)};
            const ray<T> r{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * scale), random_direction<T>(rng)};
            const reference ref = exact_roots(s, r);
            if (std::fabs(ref.l_over_r - 1) < 1e-3L) continue;
            auto want = expected_t(ref, 0, infinity<wide>);
            if (want && *want < 1e-3L * wide(s.radius)) continue;
            ++checked;
            auto got = intersect_sphere_robust(s, r, ahead<T>());
            if (got.has_value() != want.has_value()) ++wrong;
            else if (got && ulps(got->t, *want) > 4) ++bad_t;
        }
    }
    // Subnormal directions: a unit-sized scene, the direction 2^(min_exponent - 10) long.
    const T tiny = std::ldexp(T(1), std::numeric_limits<T>::min_exponent - 10);
    for (int i = 0; i < 200; ++i) {
        const sphere<T> s{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * 1e-20), T(radius(rng) * 1e-20)};
        const ray<T> r{convert<T>(vec3d(coord(rng), coord(rng), coord(rng)) * 1e-20), random_direction<T>(rng) * tiny};
        const reference ref = exact_roots(s, r);
        if (std::fabs(ref.l_over_r - 1) < 1e-3L) continue;
        auto want = expected_t(ref, 0, infinity<wide>);
        ++checked;
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (got.has_value() != want.has_value()) ++wrong;
        else if (got && ulps(got->t, *want) > 4) ++bad_t;
    }
    CHECK_MESSAGE(checked > 1000, "extreme scales: too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "spheres of radius near the limits of T (squares under- or overflow) or rays with a subnormal "
                      "direction were hit or missed wrongly: scale f, r and d by powers of two first, and call a "
                      "direction zero only when its components are");
    const bool ok_t = bad_t == 0;
    CHECK_MESSAGE(ok_t, "extreme scales: t is off by more than 4 ULPs (undo the scaling: t = t' 2^(ed - ef))");
}

// Finite inputs next to T's largest number M: o - C is 2M, beyond T, yet
// every root below is a representable number (dyadic geometry: M, M/2 and
// powers of two), so the header's 4 ULPs apply.
TEST_CASE_TEMPLATE("hidden: centres and origins near the largest finite number", T, RT_SCALARS) {
    const T M = std::numeric_limits<T>::max();
    // From -M towards a sphere of radius M centred at +M: the near root is M.
    auto hit = intersect_sphere_robust(sphere<T>{vec3<T>(0, 0, M), M}, ray<T>{vec3<T>(0, 0, -M), vec3<T>(0, 0, 1)},
                                       ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "o - C overflows T although every input is finite: scale o, C and r down first");
    CHECK(ulps(hit->t, wide(M)) <= 4);
    // Radius M/2 centred at +M/2, origin -M/2, direction (1, 0, 0)*2^k: root at M/2 * 2^-k.
    for (int k : {-3, 0, 5}) {
        const T h = M / 2;
        auto got = intersect_sphere_robust(sphere<T>{vec3<T>(h, 0, 0), h},
                                           ray<T>{vec3<T>(-h, 0, 0), vec3<T>(std::ldexp(T(1), k), 0, 0)}, ahead<T>());
        if (k < 0) {  // the root M/2 * 2^3 is beyond T: a miss, never infinity
            CHECK_FALSE(got.has_value());
            continue;
        }
        REQUIRE(got.has_value());
        CHECK(ulps(got->t, wide(std::ldexp(h, -k))) <= 4);
    }
    // From inside, at the centre of a sphere of radius M: the far root M.
    auto inside = intersect_sphere_robust(sphere<T>{vec3<T>(0, 0, 0), M}, ray<T>{vec3<T>(0, 0, 0), vec3<T>(0, 1, 0)},
                                          ahead<T>());
    REQUIRE(inside.has_value());
    CHECK(ulps(inside->t, wide(M)) <= 4);
}

TEST_CASE_TEMPLATE("hidden: rays leaving a surface (shadow and reflection rays) keep their few ULPs", T, RT_SCALARS) {
    // Origins on the surface, rounded to T (so a hair inside or outside),
    // leaving it: the far root is ~0 and c = f.f - r^2 is all cancellation.
    std::mt19937_64 rng(7013);
    std::uniform_real_distribution<double> coord(-8, 8), radius(0.5, 3), lean(-0.9, 0.9);
    int wrong = 0, bad_t = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const vec3d c(coord(rng), coord(rng), coord(rng));
        const double R = i % 3 == 0 ? 1e5 : radius(rng);
        const vec3d n = convert<double>(random_direction<double>(rng)), u = perpendicular(n, rng);
        const sphere<T> s{convert<T>(c), T(R)};
        const bool outward = i % 2 == 0;
        const vec3d dir = (outward ? n : -n) + lean(rng) * u;
        const ray<T> r{convert<T>(c + R * n), convert<T>(dir)};
        const reference ref = exact_roots(s, r);
        if (std::fabs(ref.l_over_r - 1) < 1e-3L) continue;
        auto want = expected_t(ref, 0, infinity<wide>);
        ++checked;
        auto got = intersect_sphere_robust(s, r, ahead<T>());
        if (got.has_value() != want.has_value()) ++wrong;
        else if (got && ulps(got->t, *want) > 4) ++bad_t;
    }
    CHECK_MESSAGE(checked > 2000, "secondary rays: too few cases (a test problem, not yours)");
    const bool ok = wrong == 0;
    CHECK_MESSAGE(ok, "rays starting on the surface (rounded) and leaving it: the sign of c = f.f - r^2 says whether "
                      "the origin is inside, and a c that is not accurate to its last bits gets it wrong");
    const bool ok_t = bad_t == 0;
    CHECK_MESSAGE(ok_t, "rays starting on the surface: t is off by more than 4 ULPs (c / q needs c accurate, f exact)");
}
