// Hidden tests for chapter 05 (run by the autograder only).
//
// Failure messages name the idea that went wrong but never the expected
// numbers: every check is a plain bool computed beforehand.
//
// Cases meant to land exactly on an edge or a corner are built so that any
// sensible evaluation is exact there (axis-aligned planes, small dyadic
// coordinates, rays whose t comes out exact): a miss on them is a wrong
// inequality, not rounding.
#include "05-triangle/triangle.hpp"

#include "test_support.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace rt;
using rt::ch05::barycentric;
using rt::ch05::intersect_triangle;

namespace {

using vec3l = vec3<long double>;

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

template <class T>
interval<T> everywhere() {
    return {-infinity<T>, infinity<T>};
}

template <class T>
long double tolerance() {
    return sizeof(T) == 4 ? 2e-4L : 1e-10L;
}

template <class T>
bool near_t(const std::optional<hit_record<T>>& hit, long double want) {
    return hit && std::isfinite(hit->t) && std::fabs((long double)hit->t - want) <= tolerance<T>() * (1 + std::fabs(want));
}

template <class T>
bool is_unit(const vec3<T>& v) {
    long double x = v.x, y = v.y, z = v.z;
    return std::fabs(std::sqrt(x * x + y * y + z * z) - 1) <= tolerance<T>();
}

// A reference answer computed in long double from the rounded inputs.
struct reference {
    bool crosses_plane = false;  // d . n != 0 and the triangle has area
    long double t = 0;
    vec3l point{}, bary{}, normal{};  // normal: unit, along (b - a) x (c - a)
    long double cosine = 0;           // |cos| of the angle between ray and normal
};

template <class T>
reference solve(const triangle<T>& tri, const ray<T>& r) {
    reference ref;
    const vec3l a = convert<long double>(tri.a), b = convert<long double>(tri.b), c = convert<long double>(tri.c);
    const vec3l o = convert<long double>(r.origin), d = convert<long double>(r.direction);
    const vec3l n = cross(b - a, c - a);
    const long double nn = dot(n, n), dd = dot(d, d);
    const long double den = dot(d, n);
    if (!(nn > 0) || !(dd > 0) || den == 0) return ref;
    ref.crosses_plane = true;
    ref.t = dot(a - o, n) / den;
    ref.point = o + ref.t * d;
    ref.normal = n / std::sqrt(nn);
    ref.cosine = std::fabs(den) / std::sqrt(nn * dd);
    // Barycentrics of the point on the plane, from the exact-as-possible
    // corner differences (not through the rounded hit point).
    const vec3l p = ref.point;
    ref.bary = {dot(cross(c - b, p - b), n) / nn, dot(cross(a - c, p - c), n) / nn, dot(cross(b - a, p - a), n) / nn};
    return ref;
}

// The hit's normal is the triangle's outward one, (b - a) x (c - a)
// normalised, whatever side the ray came from.
template <class T>
bool outward(const hit_record<T>& hit, const reference& ref) {
    return std::fabs(dot(convert<long double>(hit.normal), ref.normal) - 1) <= 10 * tolerance<T>();
}

template <class T>
vec3<T> mix(const triangle<T>& tri, long double wa, long double wb, long double wc) {
    const vec3l p = wa * convert<long double>(tri.a) + wb * convert<long double>(tri.b) + wc * convert<long double>(tri.c);
    return convert<T>(p);
}

template <class T>
struct random_scene {
    std::mt19937 rng;
    std::uniform_real_distribution<double> coord{-5, 5}, unit{-1, 1};
    explicit random_scene(unsigned seed) : rng(seed) {}

    vec3<T> point(double scale = 1) {
        return {T(scale * coord(rng)), T(scale * coord(rng)), T(scale * coord(rng))};
    }
    vec3<T> direction() { return {T(unit(rng)), T(unit(rng)), T(unit(rng))}; }
    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

    // A triangle that is not too thin: its smallest angle-ish measure is sane.
    triangle<T> fat_triangle() {
        for (;;) {
            triangle<T> tri{point(), point(), point(), 0};
            const vec3l a = convert<long double>(tri.a), b = convert<long double>(tri.b), c = convert<long double>(tri.c);
            const long double area2 = length(cross(b - a, c - a));
            const long double longest = std::fmax(length(b - a), std::fmax(length(c - b), length(a - c)));
            if (area2 > 0.2L * longest * longest) return tri;
        }
    }

    // A ray from somewhere around the scene through the given target point.
    ray<T> ray_through(const vec3<T>& target) {
        const vec3<T> origin = point(3);
        const T stretch = T(uniform(0.2, 3));
        return {origin, (target - origin) * stretch};
    }
};

// Rays through points with the given barycentric pattern: `outside` picks the
// coordinate to make negative (0 alpha, 1 beta, 2 gamma), or -1 for inside.
// Returns the number of wrong answers; `checked` counts judged cases.
template <class T>
int count_wrong(unsigned seed, int outside, int& checked) {
    random_scene<T> s(seed);
    int wrong = 0;
    checked = 0;
    for (int i = 0; i < 400; ++i) {
        const triangle<T> tri = s.fat_triangle();
        std::array<long double, 3> w{(long double)s.uniform(0.05, 1), (long double)s.uniform(0.05, 1),
                                     (long double)s.uniform(0.05, 1)};
        if (outside >= 0) w[size_t(outside)] = -(long double)s.uniform(0.05, 1);
        const long double sum = w[0] + w[1] + w[2];
        if (!(std::fabs(sum) > 0.2L)) continue;
        for (auto& x : w) x /= sum;
        // Normalising may flip signs: keep only the pattern asked for.
        bool pattern = true;
        for (int k = 0; k < 3; ++k) pattern = pattern && ((k == outside) ? w[size_t(k)] < -0.02L : w[size_t(k)] > 0.02L);
        if (!pattern) continue;
        const ray<T> r = s.ray_through(mix(tri, w[0], w[1], w[2]));
        const reference ref = solve(tri, r);
        if (!ref.crosses_plane || ref.cosine < 0.05L || ref.t < 1e-3L) continue;
        const long double lo = std::fmin(ref.bary.x, std::fmin(ref.bary.y, ref.bary.z));
        if (std::fabs(lo) < 0.01L) continue;  // too close to an edge to judge
        ++checked;
        auto hit = intersect_triangle(tri, r, ahead<T>());
        const bool want_hit = lo > 0;
        if (hit.has_value() != want_hit) ++wrong;
        else if (hit && !near_t(hit, ref.t)) ++wrong;
    }
    return wrong;
}

// A ray from height h above the point p of the plane z = 0, straight down
// (exact t = h for small dyadic numbers).
template <class T>
ray<T> down_onto(T x, T y, T h = 3) {
    return {{x, y, h}, {0, 0, -1}};
}

// The octahedron |x| + |y| + |z| = 1: eight faces, corners on the axes.
template <class T>
std::vector<triangle<T>> octahedron() {
    std::vector<triangle<T>> faces;
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) {
                triangle<T> f{{T(sx), 0, 0}, {0, T(sy), 0}, {0, 0, T(sz)}, 0};
                if (sx * sy * sz < 0) std::swap(f.b, f.c);  // outward winding
                faces.push_back(f);
            }
    return faces;
}

template <class T>
bool mesh_hit(const std::vector<triangle<T>>& mesh, const ray<T>& r) {
    for (const auto& f : mesh)
        if (intersect_triangle(f, r, ahead<T>())) return true;
    return false;
}

}  // namespace

TEST_CASE_TEMPLATE("hidden: rays through the inside hit", T, RT_SCALARS) {
    int checked = 0;
    const int wrong = count_wrong<T>(5001, -1, checked);
    CHECK(checked > 200);
    CHECK_MESSAGE(wrong == 0, "rays through points inside the triangle must hit it at the plane's t");
}

TEST_CASE_TEMPLATE("hidden: rays past edge b-c miss", T, RT_SCALARS) {
    int checked = 0;
    const int wrong = count_wrong<T>(5002, 0, checked);
    CHECK(checked > 100);
    CHECK_MESSAGE(wrong == 0, "a plane hit on the outer side of edge b -> c (alpha < 0) is outside the triangle: a miss");
}

TEST_CASE_TEMPLATE("hidden: rays past edge c-a miss", T, RT_SCALARS) {
    int checked = 0;
    const int wrong = count_wrong<T>(5003, 1, checked);
    CHECK(checked > 100);
    CHECK_MESSAGE(wrong == 0, "a plane hit on the outer side of edge c -> a (beta < 0) is outside the triangle: a miss");
}

TEST_CASE_TEMPLATE("hidden: rays past edge a-b miss", T, RT_SCALARS) {
    int checked = 0;
    const int wrong = count_wrong<T>(5004, 2, checked);
    CHECK(checked > 100);
    CHECK_MESSAGE(wrong == 0, "a plane hit on the outer side of edge a -> b (gamma < 0) is outside the triangle: a miss");
}

TEST_CASE_TEMPLATE("hidden: points on edges and corners count as inside", T, RT_SCALARS) {
    bool ok = true;
    // In the plane z = 0, both windings.
    const triangle<T> ccw{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const triangle<T> cw{{0, 0, 0}, {0, 2, 0}, {2, 0, 0}, 0};
    const T on_edges[][2] = {{T(0.5), 0}, {T(1.5), 0}, {0, T(0.25)}, {0, T(1.75)}, {T(1.5), T(0.5)}, {T(0.25), T(1.75)},
                             {0, 0},      {2, 0},      {0, 2}};
    for (const auto& p : on_edges) {
        ok = ok && near_t(intersect_triangle(ccw, down_onto(p[0], p[1]), ahead<T>()), 3);
        ok = ok && near_t(intersect_triangle(cw, down_onto(p[0], p[1]), ahead<T>()), 3);
        ok = ok && near_t(intersect_triangle(ccw, ray<T>{{p[0], p[1], -2}, {0, 0, 1}}, ahead<T>()), 2);
    }
    // In the plane y = -1, hit along -y.
    const triangle<T> floor{{-2, -1, -2}, {2, -1, -2}, {0, -1, 2}, 0};
    const T on_floor[][2] = {{T(1.5), -1}, {T(-1.5), -1}, {T(0.5), -2}, {0, 2}, {2, -2}};
    for (const auto& p : on_floor)
        ok = ok && near_t(intersect_triangle(floor, ray<T>{{p[0], 3, p[1]}, {0, -1, 0}}, ahead<T>()), 4);
    CHECK_MESSAGE(ok, "edges and corners belong to the triangle: each edge test must accept 0 (>= 0, not > 0)");
}

TEST_CASE_TEMPLATE("hidden: clockwise and counter-clockwise triangles both hit", T, RT_SCALARS) {
    random_scene<T> s(5005);
    int wrong = 0;
    for (int i = 0; i < 200; ++i) {
        const triangle<T> tri = s.fat_triangle();
        const triangle<T> flipped{tri.a, tri.c, tri.b, 0};
        const ray<T> r = s.ray_through(mix(tri, 0.3L, 0.3L, 0.4L));
        const reference ref = solve(tri, r);
        if (!ref.crosses_plane || ref.cosine < 0.05L || ref.t < 1e-3L) continue;
        if (!near_t(intersect_triangle(tri, r, ahead<T>()), ref.t)) ++wrong;
        if (!near_t(intersect_triangle(flipped, r, ahead<T>()), ref.t)) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "the inside test must not depend on the order of the corners or on the side the ray comes from");
}

TEST_CASE_TEMPLATE("hidden: shared edges of a quad leave no crack", T, RT_SCALARS) {
    bool ok = true;
    // The square (0,0)-(4,0)-(4,4)-(0,4) in z = 0, split along either diagonal.
    const triangle<T> split1[2] = {{{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, 0}, {{0, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0}};
    const triangle<T> split2[2] = {{{4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0}, {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 0}};
    for (T s : {T(0.125), T(0.5), T(1), T(2.25), T(3.5), T(3.875)}) {
        // Straight down onto the diagonals, and obliquely with a dyadic slope.
        const ray<T> r1 = down_onto(s, s), r2 = down_onto(s, 4 - s);
        const ray<T> r3{{s - T(0.75), s - T(0.75), 3}, {T(0.25), T(0.25), -1}};
        ok = ok && (intersect_triangle(split1[0], r1, ahead<T>()) || intersect_triangle(split1[1], r1, ahead<T>()));
        ok = ok && (intersect_triangle(split1[0], r3, ahead<T>()) || intersect_triangle(split1[1], r3, ahead<T>()));
        ok = ok && (intersect_triangle(split2[0], r2, ahead<T>()) || intersect_triangle(split2[1], r2, ahead<T>()));
    }
    CHECK_MESSAGE(ok, "a ray through the shared diagonal of two triangles must hit at least one of them: no cracks");
}

TEST_CASE_TEMPLATE("hidden: a closed mesh is watertight", T, RT_SCALARS) {
    const auto mesh = octahedron<T>();
    int holes = 0;
    // Aimed exactly at edges and corners from the centre (exact t = 1).
    const T aims[][3] = {{T(0.25), T(0.75), 0}, {T(-0.5), 0, T(0.5)}, {0, T(-0.125), T(-0.875)}, {1, 0, 0},
                         {0, -1, 0},            {0, 0, 1},            {T(0.75), T(-0.25), 0}};
    for (const auto& a : aims)
        if (!mesh_hit(mesh, ray<T>{{0, 0, 0}, {a[0], a[1], a[2]}})) ++holes;
    // Random rays from random points inside.
    std::mt19937 rng(5006);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 2000; ++i) {
        const vec3<T> o{T(0.2 * u(rng)), T(0.2 * u(rng)), T(0.2 * u(rng))};
        const vec3<T> d{T(u(rng)), T(u(rng)), T(u(rng))};
        if (!(length(d) > T(0.01))) continue;
        if (!mesh_hit(mesh, ray<T>{o, d})) ++holes;
    }
    CHECK_MESSAGE(holes == 0, "every ray from inside a closed mesh must hit some face: rays slipped through the seams");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates sum to 1", T, RT_SCALARS) {
    random_scene<T> s(5007);
    int wrong = 0;
    for (int i = 0; i < 300; ++i) {
        const triangle<T> tri = s.fat_triangle();
        const long double wb = s.uniform(-1, 2), wc = s.uniform(-1, 2);
        const vec3<T> w = barycentric(tri, mix(tri, 1 - wb - wc, wb, wc));
        const long double sum = (long double)w.x + w.y + w.z;
        if (!(std::fabs(sum - 1) <= 100 * tolerance<T>())) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "alpha + beta + gamma must be 1: each is a sub-area divided by the whole area");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates rebuild the point", T, RT_SCALARS) {
    random_scene<T> s(5008);
    int wrong = 0;
    for (int i = 0; i < 300; ++i) {
        const triangle<T> tri = s.fat_triangle();
        const long double wb = s.uniform(-0.5, 1.5), wc = s.uniform(-0.5, 1.5);
        const vec3<T> p = mix(tri, 1 - wb - wc, wb, wc);
        const vec3<T> w = barycentric(tri, p);
        const vec3l back = (long double)w.x * convert<long double>(tri.a) + (long double)w.y * convert<long double>(tri.b) +
                           (long double)w.z * convert<long double>(tri.c);
        if (!(length(back - convert<long double>(p)) <= 100 * tolerance<T>() * (1 + length(convert<long double>(p))))) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "alpha a + beta b + gamma c must give back the point the coordinates were computed for");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates come in corner order", T, RT_SCALARS) {
    const triangle<T> tri{{1, 2, 3}, {5, 2, 3}, {1, 6, 5}, 0};
    const auto is = [](const vec3<T>& w, long double x, long double y, long double z) {
        return std::fabs(w.x - x) <= tolerance<T>() && std::fabs(w.y - y) <= tolerance<T>() &&
               std::fabs(w.z - z) <= tolerance<T>();
    };
    bool ok = is(barycentric(tri, tri.a), 1, 0, 0) && is(barycentric(tri, tri.b), 0, 1, 0) &&
              is(barycentric(tri, tri.c), 0, 0, 1) && is(barycentric(tri, mix(tri, 0.5L, 0.5L, 0)), 0.5L, 0.5L, 0) &&
              is(barycentric(tri, mix(tri, 0.125L, 0.25L, 0.625L)), 0.125L, 0.25L, 0.625L);
    CHECK_MESSAGE(ok, "the coordinates are (alpha, beta, gamma) for corners (a, b, c), in that order");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates are negative outside the triangle", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const vec3<T> past_bc = barycentric(tri, vec3<T>{2, 2, 0});
    const vec3<T> past_ca = barycentric(tri, vec3<T>{-1, 1, 0});
    const vec3<T> past_ab = barycentric(tri, vec3<T>{1, -1, 0});
    bool ok = past_bc.x < T(0) && past_bc.y > T(0) && past_bc.z > T(0) && past_ca.y < T(0) && past_ca.x > T(0) &&
              past_ca.z > T(0) && past_ab.z < T(0) && past_ab.x > T(0) && past_ab.y > T(0);
    CHECK_MESSAGE(ok, "the sub-areas are signed: beyond an edge the coordinate of the opposite corner is negative");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates match a higher-precision answer", T, RT_SCALARS) {
    random_scene<T> s(5009);
    int wrong = 0;
    for (int i = 0; i < 300; ++i) {
        const triangle<T> tri = s.fat_triangle();
        const vec3<T> p = mix(tri, s.uniform(-1, 1), s.uniform(-1, 1), s.uniform(-1, 1));
        // Project the rounded point onto the plane in long double for the reference.
        const vec3l a = convert<long double>(tri.a), b = convert<long double>(tri.b), c = convert<long double>(tri.c);
        const vec3l n = cross(b - a, c - a);
        const long double nn = dot(n, n);
        const vec3l q = convert<long double>(p) - dot(convert<long double>(p) - a, n) / nn * n;
        const vec3l want{dot(cross(c - b, q - b), n) / nn, dot(cross(a - c, q - c), n) / nn, dot(cross(b - a, q - a), n) / nn};
        const vec3<T> got = barycentric(tri, p);
        const long double err = std::fmax(std::fabs(got.x - want.x), std::fmax(std::fabs(got.y - want.y), std::fabs(got.z - want.z)));
        if (!(err <= 100 * tolerance<T>())) ++wrong;
    }
    CHECK_MESSAGE(wrong == 0, "barycentric coordinates differ from the signed-area ratios");
}

TEST_CASE_TEMPLATE("hidden: degenerate triangles are misses", T, RT_SCALARS) {
    const triangle<T> collinear{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, 0};
    const triangle<T> collinear3d{{1, 2, 3}, {2, 4, 6}, {3, 6, 9}, 0};
    const triangle<T> two_same{{1, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0};
    const triangle<T> one_point{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 0};
    bool ok = !intersect_triangle(collinear, down_onto(T(1), T(1)), everywhere<T>()).has_value() &&
              !intersect_triangle(collinear, ray<T>{{1, 1, 3}, {T(0.5), T(0.25), -1}}, everywhere<T>()).has_value() &&
              !intersect_triangle(collinear3d, ray<T>{{0, 0, 0}, {2, 4, 6}}, everywhere<T>()).has_value() &&
              !intersect_triangle(collinear3d, ray<T>{{0, 4, 0}, {2, 0, 6}}, everywhere<T>()).has_value() &&
              !intersect_triangle(two_same, ray<T>{{T(0.5), T(0.5), 3}, {0, 0, -1}}, everywhere<T>()).has_value() &&
              !intersect_triangle(one_point, ray<T>{{0, 0, 0}, {1, 1, 1}}, everywhere<T>()).has_value();
    CHECK_MESSAGE(ok, "a triangle of zero area has no plane and no inside: every ray misses it, never a NaN hit");
}

TEST_CASE_TEMPLATE("hidden: barycentric coordinates of a degenerate triangle are NaN", T, RT_SCALARS) {
    const triangle<T> collinear{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, 0};
    const triangle<T> one_point{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, 0};
    const vec3<T> w1 = barycentric(collinear, vec3<T>{1, 1, 0});
    const vec3<T> w2 = barycentric(one_point, vec3<T>{1, 1, 1});
    bool ok = std::isnan(w1.x) && std::isnan(w1.y) && std::isnan(w1.z) && std::isnan(w2.x) && std::isnan(w2.y) &&
              std::isnan(w2.z);
    CHECK_MESSAGE(ok, "a zero-area triangle has no barycentric coordinates: the contract asks for NaN in all three");
}

TEST_CASE_TEMPLATE("hidden: parallel rays are misses", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const triangle<T> slanted{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0};
    bool ok = !intersect_triangle(tri, ray<T>{{-1, T(0.5), 1}, {1, 0, 0}}, everywhere<T>()).has_value() &&
              !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), -1}, {1, 1, 0}}, everywhere<T>()).has_value() &&
              !intersect_triangle(slanted, ray<T>{{0, 0, 0}, {1, -1, 0}}, everywhere<T>()).has_value();
    CHECK_MESSAGE(ok, "d . n = 0: a ray parallel to the triangle's plane never crosses it, a miss");
}

TEST_CASE_TEMPLATE("hidden: rays lying in the triangle plane are misses", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const triangle<T> slanted{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0};
    bool ok = !intersect_triangle(tri, ray<T>{{-1, T(0.5), 0}, {1, 0, 0}}, everywhere<T>()).has_value() &&
              !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), 0}, {1, 1, 0}}, everywhere<T>()).has_value() &&
              !intersect_triangle(slanted, ray<T>{{1, 0, 0}, {-1, 1, 0}}, everywhere<T>()).has_value();
    CHECK_MESSAGE(ok, "a ray inside the triangle's plane gives t = 0 / 0: a miss, never a NaN hit");
}

TEST_CASE_TEMPLATE("hidden: the normal follows the winding, from either side", T, RT_SCALARS) {
    random_scene<T> s(5010);
    int wrong = 0, hits = 0, from_behind = 0;
    for (int i = 0; i < 300; ++i) {
        const triangle<T> tri = s.fat_triangle();
        const ray<T> r = s.ray_through(mix(tri, 0.2L, 0.5L, 0.3L));
        const reference ref = solve(tri, r);
        if (!ref.crosses_plane || ref.cosine < 0.05L) continue;
        auto hit = intersect_triangle(tri, r, everywhere<T>());
        if (!hit) { ++wrong; continue; }
        ++hits;
        if (dot(convert<long double>(r.direction), ref.normal) > 0) ++from_behind;
        if (!outward(*hit, ref)) ++wrong;
    }
    CHECK(hits > 200);
    CHECK(from_behind > 50);
    CHECK_MESSAGE(wrong == 0, "the normal is (b - a) x (c - a) normalised, whichever side the ray comes from (the "
                              "one face rule, not the exercise, turns it towards the ray)");
}

TEST_CASE_TEMPLATE("hidden: the normal is unit length", T, RT_SCALARS) {
    bool ok = true;
    for (T size : {T(0.001), T(0.1), T(1), T(30), T(1000)}) {
        const triangle<T> tri{{0, 0, 0}, {size, 0, 0}, {0, 0, size}, 0};  // normal along -y
        auto hit = intersect_triangle(tri, ray<T>{{size / 4, 5, size / 4}, {0, -1, 0}}, ahead<T>());
        ok = ok && near_t(hit, 5) && is_unit(hit->normal);
    }
    CHECK_MESSAGE(ok, "(b - a) x (c - a) has length twice the area: normalise it for the hit record");
}

TEST_CASE_TEMPLATE("hidden: triangles behind the origin are not hit", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    bool ok = !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), 3}, {0, 0, 1}}, ahead<T>()).has_value() &&
              !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), -3}, {0, 0, -1}}, ahead<T>()).has_value() &&
              !intersect_triangle(tri, ray<T>{{1, 1, 2}, {T(0.25), T(0.25), 1}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a crossing at negative t is behind the ray's origin: only tmin < t counts");
}

TEST_CASE_TEMPLATE("hidden: perspective rays skip hits before the image plane", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const auto front = interval<T>::in_front_of_image_plane();
    bool ok = !intersect_triangle(tri, down_onto(T(0.5), T(0.5), T(0.75)), front).has_value() &&
              near_t(intersect_triangle(tri, down_onto(T(0.5), T(0.5), T(1.25)), front), 1.25L);
    CHECK_MESSAGE(ok, "with the image plane at t = 1, a crossing at t <= 1 is not visible");
}

TEST_CASE_TEMPLATE("hidden: hits beyond tmax are rejected", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const ray<T> r = down_onto(T(0.5), T(0.5), T(5));
    bool ok = !intersect_triangle(tri, r, interval<T>{0, T(4.5)}).has_value() &&
              near_t(intersect_triangle(tri, r, interval<T>{0, T(5.5)}), 5) &&
              !intersect_triangle(tri, r, interval<T>{T(-10), T(1)}).has_value();
    CHECK_MESSAGE(ok, "a hit counts only when tmin < t < tmax: a crossing past tmax is not in range");
}

TEST_CASE_TEMPLATE("hidden: the interval is open at both ends", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const ray<T> r = down_onto(T(0.5), T(0.5));  // exactly t = 3
    bool ok = !intersect_triangle(tri, r, interval<T>{0, 3}).has_value() &&
              !intersect_triangle(tri, r, interval<T>{3, 10}).has_value() &&
              near_t(intersect_triangle(tri, r, interval<T>{T(2.5), T(3.5)}), 3) &&
              !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), 0}, {0, 0, 1}}, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "the rule is strict, tmin < t < tmax: a crossing exactly at tmin or tmax does not count");
}

TEST_CASE_TEMPLATE("hidden: the object field is left at -1", T, RT_SCALARS) {
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 5};
    auto hit = intersect_triangle(tri, down_onto(T(0.5), T(0.5)), ahead<T>());
    bool ok = hit.has_value() && hit->object == -1;
    CHECK_MESSAGE(ok, "intersect_triangle does not know the triangle's index in a scene: leave object at -1");
}

TEST_CASE_TEMPLATE("hidden: NaN inputs are misses", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const triangle<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
    const ray<T> r = down_onto(T(0.5), T(0.5));
    bool ok = !intersect_triangle(tri, ray<T>{{nan, T(0.5), 3}, {0, 0, -1}}, everywhere<T>()).has_value() &&
              !intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), 3}, {0, 0, nan}}, everywhere<T>()).has_value() &&
              !intersect_triangle(triangle<T>{{0, 0, nan}, {2, 0, 0}, {0, 2, 0}, 0}, r, everywhere<T>()).has_value() &&
              !intersect_triangle(triangle<T>{{0, 0, 0}, {nan, 0, 0}, {0, 2, 0}, 0}, r, everywhere<T>()).has_value() &&
              !intersect_triangle(triangle<T>{{0, 0, 0}, {2, 0, 0}, {0, nan, 0}, 0}, r, everywhere<T>()).has_value();
    CHECK_MESSAGE(ok, "a NaN anywhere in the ray or the triangle must give a miss: comparisons written so NaN fails them");
}

TEST_CASE_TEMPLATE("hidden: very small and very large triangles are still hit", T, RT_SCALARS) {
    // So small or so large that (b - a) x (c - a) . n underflows or overflows in T.
    const T tiny = sizeof(T) == 4 ? T(1e-12) : T(1e-80);
    const T subnormal = std::numeric_limits<T>::denorm_min() * T(1 << 20);  // 20 bits of precision left
    const T huge = sizeof(T) == 4 ? T(1e12) : T(1e80);
    bool ok = true;
    for (T size : {tiny, subnormal, huge}) {
        const triangle<T> tri{{0, 0, 0}, {2 * size, 0, 0}, {0, 2 * size, 0}, 0};
        auto inside = intersect_triangle(tri, ray<T>{{size / 2, size / 2, size}, {0, 0, -size}}, ahead<T>());
        auto outside = intersect_triangle(tri, ray<T>{{2 * size, 2 * size, size}, {0, 0, -size}}, ahead<T>());
        const vec3<T> w = barycentric(tri, vec3<T>{size / 2, size, 0});
        ok = ok && near_t(inside, 1) && is_unit(inside->normal) && !outside.has_value() &&
             std::fabs(w.x - T(0.25)) <= T(tolerance<T>()) && std::fabs(w.y - T(0.25)) <= T(tolerance<T>()) &&
             std::fabs(w.z - T(0.5)) <= T(tolerance<T>());
    }
    CHECK_MESSAGE(ok, "a triangle's size does not change what is inside it: avoid overflow and underflow in the areas");
}

TEST_CASE_TEMPLATE("hidden: random rays agree with a higher-precision answer", T, RT_SCALARS) {
    random_scene<T> s(20261105);
    int wrong_hit_or_miss = 0, wrong_t = 0, bad_record = 0, checked = 0;
    for (int i = 0; i < 3000; ++i) {
        const triangle<T> tri{s.point(), s.point(), s.point(), 0};
        {  // skip slivers: their inside test is ill-conditioned near every edge
            const vec3l a = convert<long double>(tri.a), b = convert<long double>(tri.b), c = convert<long double>(tri.c);
            const long double longest = std::fmax(length(b - a), std::fmax(length(c - b), length(a - c)));
            if (!(length(cross(b - a, c - a)) > 0.01L * longest * longest)) continue;
        }
        const ray<T> r = s.ray_through(s.point(0.5));
        const interval<T> range{T(s.uniform(-1, 0.5)), T(s.uniform(0.5, 3))};
        const reference ref = solve(tri, r);
        if (!ref.crosses_plane || ref.cosine < 0.05L) continue;
        const long double lo = std::fmin(ref.bary.x, std::fmin(ref.bary.y, ref.bary.z));
        if (std::fabs(lo) < 1e-3L) continue;  // too close to an edge to judge
        if (std::fabs(ref.t - range.min) < 1e-3L * (1 + std::fabs(ref.t)) ||
            std::fabs(ref.t - range.max) < 1e-3L * (1 + std::fabs(ref.t)))
            continue;  // too close to an end of the range to judge
        const bool want_hit = lo > 0 && ref.t > range.min && ref.t < range.max;
        ++checked;
        auto hit = intersect_triangle(tri, r, range);
        if (hit.has_value() != want_hit) { ++wrong_hit_or_miss; continue; }
        if (!hit) continue;
        if (!near_t(hit, ref.t)) ++wrong_t;
        const vec3l at = convert<long double>(r.origin) + (long double)hit->t * convert<long double>(r.direction);
        const bool point_ok = length(convert<long double>(hit->point) - at) <= 10 * tolerance<T>() * (1 + length(at));
        const bool normal_ok = is_unit(hit->normal) && outward(*hit, ref);
        if (!point_ok || !normal_ok) ++bad_record;
    }
    CHECK(checked > 2000);
    CHECK_MESSAGE(wrong_hit_or_miss == 0, "random rays: some hits were reported as misses or misses as hits");
    CHECK_MESSAGE(wrong_t == 0, "random rays: some hits returned a t that is not the crossing of ray and plane");
    CHECK_MESSAGE(bad_record == 0, "random rays: some hit records had a wrong point or normal");
}
