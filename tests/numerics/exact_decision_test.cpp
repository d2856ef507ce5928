// Exact decisions: parallel, in-plane and degenerate inputs whose exact
// determinant is 0 although the rounded one is not. Each case is
// built so that its exact answer is known (dyadic geometry, every
// construction step checked to be exact), and each family is checked to be
// stiff: the plain rounded dot product or determinant is non-zero for many
// of its cases, so the rounded-zero shortcut cannot pass these tests.
#include "exact_sign.hpp"
#include "numerics_support.hpp"

#include <random>

using namespace rt;
using namespace rt::numerics_test;

namespace {

// x + y exactly representable in T?
template <class T>
bool sum_is_exact(T x, T y) {
    return rt::two_sum(x, y).lo == 0 && std::isfinite(x + y);
}
template <class T>
bool sum_is_exact(const vec3<T>& x, const vec3<T>& y) {
    return sum_is_exact(x.x, y.x) && sum_is_exact(x.y, y.y) && sum_is_exact(x.z, y.z);
}

// A random vector of integers times 2^-12, up to 2^12 in size: products of
// two such components need about 24 bits, so float rounds them.
template <class T>
vec3<T> dyadic(std::mt19937& rng, int bits = 12) {
    std::uniform_int_distribution<int> k(-(1 << bits) + 1, (1 << bits) - 1);
    return vec3<T>(std::ldexp(T(k(rng)), -bits), std::ldexp(T(k(rng)), -bits), std::ldexp(T(k(rng)), -bits));
}

// A point with a full significand, so that sums with it round.
template <class T>
vec3<T> full_point(std::mt19937& rng) {
    std::uniform_real_distribution<T> u(T(0.5), T(1));
    return vec3<T>(u(rng), u(rng), u(rng));
}

// The exactly parallel pair from exact_sign.hpp's comment, for T's width:
// with h = digits / 2 + 1, d.n = 0 exactly while the rounded d.n = 2^-(2h+1).
template <class T>
void parallel_pair(vec3<T>& d, vec3<T>& n, T tail = T(1)) {
    const int h = std::numeric_limits<T>::digits / 2 + 1;
    d = vec3<T>(1 + std::ldexp(T(1), -h), 1 + std::ldexp(T(1), -h) + std::ldexp(T(1), -h - 1),
                tail * std::ldexp(T(1), -2 * h - 1));
    n = vec3<T>(-(1 + std::ldexp(T(1), -h - 1)), 1, 1);
}

}  // namespace

TEST_CASE_TEMPLATE("exact_dot_sign decides the sign where the rounded dot product is wrong", T, RT_SCALARS) {
    vec3<T> d, n;
    parallel_pair(d, n);
    REQUIRE_MESSAGE(dot(d, n) != T(0), "the case must be stiff: the rounded d.n is not 0");
    CHECK(fm::exact_dot_sign(d, n) == 0);
    CHECK(fm::parallel_exactly(d, n));
    // A quarter and three halves of the lost term: exact d.n = -3/4 and +1/2
    // of it, while the rounded d.n is positive in both.
    parallel_pair(d, n, T(0.25));
    CHECK(fm::exact_dot_sign(d, n) == -1);
    parallel_pair(d, n, T(1.5));
    CHECK(fm::exact_dot_sign(d, n) == 1);
    CHECK(!fm::parallel_exactly(d, n));
    // Subnormal and huge vectors (scaled inside, no sign changes).
    const T tiny = std::numeric_limits<T>::denorm_min();
    CHECK(fm::exact_dot_sign(vec3<T>(tiny, 0, 0), vec3<T>(tiny, 0, 0)) == 1);
    CHECK(fm::exact_dot_sign(vec3<T>(std::numeric_limits<T>::max(), 0, 0), vec3<T>(-tiny, 0, 0)) == -1);
}

TEST_CASE_TEMPLATE("plane formulations miss exactly parallel and in-plane rays whose rounded d.n is not 0", T,
                   RT_SCALARS) {
    vec3<T> d, n;
    parallel_pair(d, n);
    const vec3<T> o(0, 0, 0);
    const interval<T> all{T(0), infinity<T>};
    for (const auto& entry : fm::plane_formulations()) {
        // Parallel, one unit off the plane: the rounded quotient is ~1e8 (float).
        plane<T> off{vec3<T>(0, 0, 1), n, 0};
        CHECK_MESSAGE(!entry.template fn<T>()(ray<T>{o, d}, off, all), entry.name << ": parallel ray");
        // In the plane: the plane goes through o + d, i.e. through the ray.
        plane<T> in{d, n, 0};
        CHECK_MESSAGE(!entry.template fn<T>()(ray<T>{o, d}, in, all), entry.name << ": ray in the plane");
        // A subnormal, non-zero direction towards the plane z = 2^-100 hits it
        // at t = 2^-100 / tiny (a power of two: exact).
        const T tiny = std::ldexp(std::numeric_limits<T>::min(), -3);
        plane<T> ahead{vec3<T>(0, 0, std::ldexp(T(1), -100)), vec3<T>(0, 0, 1), 0};
        auto hit = entry.template fn<T>()(ray<T>{o, vec3<T>(0, 0, tiny)}, ahead, all);
        REQUIRE_MESSAGE(hit.has_value(), entry.name << ": a subnormal direction is not a zero direction");
        CHECK(hit->t == std::ldexp(T(1), -100 - std::ilogb(tiny)));
    }
}

TEST_CASE_TEMPLATE("triangle formulations miss in-plane rays and degenerate triangles built exactly", T,
                   RT_SCALARS) {
    std::mt19937 rng(11);
    std::size_t in_plane = 0, degenerate = 0, stiff = 0;
    std::vector<std::string> wrong;
    for (int i = 0; i < 400; ++i) {
        const vec3<T> a = full_point<T>(rng), e1 = dyadic<T>(rng), e2 = dyadic<T>(rng);
        const bool flat_case = i % 2 == 1;  // odd: degenerate triangle (c - a = 3 e1)
        const vec3<T> b = a + e1, c = flat_case ? a + T(3) * e1 : a + e2;
        if (!sum_is_exact(a, e1) || !sum_is_exact(a, flat_case ? T(3) * e1 : e2)) continue;
        // A ray in the triangle's plane: origin a + e2 / 2 - e1 (exact), direction e1 + e2 / 4 (exact), or,
        // for the degenerate triangle, any ray through the segment.
        vec3<T> o, d;
        if (flat_case) {
            o = full_point<T>(rng) + vec3<T>(0, 0, 2);
            d = (a + T(2) * e1) - o;  // rounded: the ray passes near the segment, the triangle still has no area
        } else {
            o = a + T(0.5) * e2 - e1;
            d = e1 + T(0.25) * e2;
            if (!sum_is_exact(a, T(0.5) * e2) || !sum_is_exact(a + T(0.5) * e2, -e1) || !sum_is_exact(e1, T(0.25) * e2))
                continue;
        }
        ++(flat_case ? degenerate : in_plane);
        const triangle<T> tri{a, b, c, 0};
        stiff += dot(b - a, cross(d, c - a)) != T(0);
        for (const auto& entry : fm::triangle_formulations())
            if (entry.template fn<T>()(ray<T>{o, d}, tri, interval<T>{T(0), infinity<T>}))
                wrong.push_back(entry.name + (flat_case ? " (degenerate) " : " (in plane) ") + std::to_string(i));
    }
    REQUIRE(in_plane >= 50);
    REQUIRE(degenerate >= 50);
    if constexpr (std::is_same_v<T, float>)
        REQUIRE_MESSAGE(stiff >= 20, "the family must be stiff: a rounded determinant that is not 0");
    CHECK_MESSAGE(wrong.empty(), "a ray lying in the triangle's plane and a triangle with no area are misses, "
                                 "decided exactly; false hits: "
                                     << wrong.size() << (wrong.empty() ? "" : ", first " + wrong.front()));
    // And a subnormal direction straight at a triangle is a hit.
    const T tiny = std::ldexp(std::numeric_limits<T>::min(), -3);
    const T z = std::ldexp(T(1), -100);
    const triangle<T> ahead{vec3<T>(-1, -1, z), vec3<T>(1, -1, z), vec3<T>(0, 1, z), 0};
    for (const auto& entry : fm::triangle_formulations())
        CHECK_MESSAGE(entry.template fn<T>()(ray<T>{vec3<T>(0, 0, 0), vec3<T>(0, 0, tiny)}, ahead,
                                             interval<T>{T(0), infinity<T>}),
                      entry.name << ": a subnormal direction is not a zero direction");
}

TEST_CASE_TEMPLATE("plane formulations: a normal of any finite length, and subnormal directions, give the exact t", T,
                   RT_SCALARS) {
    // The normal's length cancels from t; 2^(max_exponent - 2) makes (q - o).n overflow unless it is scaled.
    const int top = std::numeric_limits<T>::max_exponent - 2, low = std::numeric_limits<T>::min_exponent;
    for (const fm::plane_formulation& f : fm::plane_formulations()) {
        CAPTURE(f.name);
        for (int e : {top, -top, low - 20}) {
            const T big = std::ldexp(T(1), e);
            const plane<T> p{vec3<T>(4, 0, 0), vec3<T>(big, big, 0)};
            auto hit = f.fn<T>()(ray<T>{vec3<T>(0, 0, 0), vec3<T>(1, 0, 0)}, p, interval<T>{T(0), infinity<T>});
            REQUIRE(hit.has_value());
            CHECK(hit->t == T(4));
            CHECK(std::isfinite(hit->point.x));
        }
        // A subnormal direction 2^(low - 10) (1, 1/2, 1) towards the plane y + z = 2^-40.
        const plane<T> p{vec3<T>(0, 0, std::ldexp(T(1), -40)), vec3<T>(0, 1, 1)};
        const vec3<T> d(std::ldexp(T(1), low - 10), std::ldexp(T(1), low - 11), std::ldexp(T(1), low - 10));
        // d.n = 3 * 2^(low - 11): the exact t = 2^-40 / d.n = 2^(-29 - low) / 3, rounded once.
        auto hit = f.fn<T>()(ray<T>{vec3<T>(0, 0, 0), d}, p, interval<T>{T(0), infinity<T>});
        REQUIRE(hit.has_value());
        CHECK(hit->t == std::ldexp(T(1), -29 - low) / T(3));
    }
}

TEST_CASE_TEMPLATE("exact_orientation_sign agrees with integer arithmetic on small integer cases", T, RT_SCALARS) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> k(-20, 20);
    for (int i = 0; i < 300; ++i) {
        long long v[12];
        for (long long& x : v) x = k(rng);
        // d.((b - a) x (c - a)) in exact integers.
        long long e1[3] = {v[6] - v[3], v[7] - v[4], v[8] - v[5]}, e2[3] = {v[9] - v[3], v[10] - v[4], v[11] - v[5]};
        long long cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        long long det = v[0] * cr[0] + v[1] * cr[1] + v[2] * cr[2];
        auto V = [&](int j) { return vec3<T>(T(v[j]), T(v[j + 1]), T(v[j + 2])); };
        CHECK(fm::exact_orientation_sign(V(0), V(3), V(6), V(9)) == (det > 0) - (det < 0));
    }
}

// ---------------------------------------------------------------------------
// The renderer's plane and triangle kernels (tools/render/fast_path_kernels.hpp)
// make the same decisions, driven as fast_path.cpp drives them: the lane
// function first, the exact one for the lanes it was unsure of. Where the
// exact value is not 0 they must give the plain formula's very bits.
#if __has_include("fast_path_kernels.hpp")
#include "fast_path_kernels.hpp"

namespace rk = rt::render_tool;

namespace render_kernels {

// The plane kernel as a lane of fast_path.cpp runs it.
template <class T>
T plane_lane(const vec3<T>& point, const vec3<T>& n, const ray<T>& r, T tmin) {
    const T num = n.x * (point.x - r.origin.x) + n.y * (point.y - r.origin.y) + n.z * (point.z - r.origin.z);
    int unsure = 0;
    const T t = rk::plane_t(num, n.x, n.y, n.z, r.direction.x, r.direction.y, r.direction.z, tmin, unsure);
    return unsure ? rk::plane_t_exact(num, n.x, n.y, n.z, r.direction.x, r.direction.y, r.direction.z, tmin, n) : t;
}

// The plain quotient, without any decision: what the kernel computed before.
template <class T>
T plane_plain(const vec3<T>& point, const vec3<T>& n, const ray<T>& r) {
    const T num = n.x * (point.x - r.origin.x) + n.y * (point.y - r.origin.y) + n.z * (point.z - r.origin.z);
    return num / (n.x * r.direction.x + n.y * r.direction.y + n.z * r.direction.z);
}

// The triangle kernel as a lane of fast_path.cpp runs it on the triangle
// with corners a, b, c: corner a and the rounded edges e1 = b - a,
// e2 = c - a in the lanes, the corners in the exact decision. bound < 0
// gives Moeller-Trumbore without the decision.
template <class T>
T triangle_lane_corners(const vec3<T>& a, const vec3<T>& b, const vec3<T>& c, const ray<T>& r, T tmin,
                        bool decide = true) {
    const vec3<T> e1 = b - a, e2 = c - a;
    const vec3<T> s = r.origin - a, q = cross(s, e1), d = r.direction;
    const T bound = decide ? rk::flat_scale(e1.x, e1.y, e1.z, e2.x, e2.y, e2.z) * rk::direction_max(d.x, d.y, d.z) +
                                 rk::flat_tiny<T>()
                           : T(-1);
    int unsure = 0;
    const T t = rk::triangle_t(s.x, s.y, s.z, q.x, q.y, q.z, e1.x, e1.y, e1.z, e2.x, e2.y, e2.z, d.x, d.y, d.z, tmin,
                               bound, unsure);
    if (!unsure) return t;
    return rk::triangle_t_exact(s.x, s.y, s.z, q.x, q.y, q.z, e1.x, e1.y, e1.z, e2.x, e2.y, e2.z, d.x, d.y, d.z, tmin, a,
                                b, c);
}

// The same from corner a and edges e1, e2 (the tests build a + e1 and a + e2 exact).
template <class T>
T triangle_lane(const vec3<T>& a, const vec3<T>& e1, const vec3<T>& e2, const ray<T>& r, T tmin, bool decide = true) {
    return triangle_lane_corners(a, a + e1, a + e2, r, tmin, decide);
}

}  // namespace render_kernels

// The plane kernel as fast_path.cpp runs it on a scene plane: the lanes use
// the unit normal (normalised in double, rounded to T), the exact decision
// the scene's normal.
template <class T>
T plane_lane_scene(const vec3<T>& point, const vec3<T>& normal, const ray<T>& r, T tmin) {
    const vec3d u = normalize(convert<double>(normal));
    const vec3<T> n(T(u.x), T(u.y), T(u.z));
    const T num = n.x * (point.x - r.origin.x) + n.y * (point.y - r.origin.y) + n.z * (point.z - r.origin.z);
    int unsure = 0;
    const T t = rk::plane_t(num, n.x, n.y, n.z, r.direction.x, r.direction.y, r.direction.z, tmin, unsure);
    return unsure ? rk::plane_t_exact(num, n.x, n.y, n.z, r.direction.x, r.direction.y, r.direction.z, tmin, normal)
                  : t;
}

TEST_CASE_TEMPLATE("render plane kernel: rays exactly parallel to a scene plane whose unit normal rounds miss", T,
                   RT_SCALARS) {
    // Integer normal n and direction d = n x m (exactly perpendicular); the unit normal rounds, so d is not
    // exactly perpendicular to it. The origin is 1 to 3 units off the plane along an axis.
    std::mt19937 rng(43);
    std::uniform_int_distribution<int> c(-(1 << 8), 1 << 8), off(1, 3);
    int cases = 0, unit_not_parallel = 0, false_hits = 0;
    for (int i = 0; i < 400; ++i) {
        const vec3<T> n(T(c(rng)), T(c(rng)), T(c(rng))), m(T(c(rng)), T(c(rng)), T(c(rng)));
        const vec3<T> d = cross(n, m);  // entries below 2^18: exact
        if (d == vec3<T>(0, 0, 0)) continue;
        const vec3<T> o(T(c(rng)), T(c(rng)), T(c(rng)));
        const vec3<T> point = o + vec3<T>(T(off(rng)), 0, 0);
        if (n.x == 0) continue;  // the origin must be off the plane
        REQUIRE(fm::exact_dot_sign(d, n) == 0);
        ++cases;
        const vec3d u = normalize(convert<double>(n));
        unit_not_parallel += fm::exact_dot_sign(d, vec3<T>(T(u.x), T(u.y), T(u.z))) != 0;
        false_hits += plane_lane_scene(point, n, ray<T>{o, d}, T(0)) != infinity<T>;
        false_hits += plane_lane_scene(point, n, ray<T>{o, -d}, T(0)) != infinity<T>;
    }
    MESSAGE(cases << " exactly parallel rays, not parallel to the rounded unit normal in " << unit_not_parallel);
    REQUIRE(cases >= 300);
    REQUIRE_MESSAGE(unit_not_parallel >= 100, "stiff: unit normals that round off the perpendicular");
    CHECK(false_hits == 0);
}

TEST_CASE_TEMPLATE("render plane kernel: exactly parallel and in-plane rays miss although the rounded d.n is not 0",
                   T, RT_SCALARS) {
    // d.n = 0 exactly, rounded d.n = 2^-(2h+1) (exact_sign.hpp's pair).
    const int h = std::numeric_limits<T>::digits / 2 + 1;
    const vec3<T> d(1 + std::ldexp(T(1), -h), 1 + std::ldexp(T(1), -h) + std::ldexp(T(1), -h - 1),
                    std::ldexp(T(1), -2 * h - 1));
    const vec3<T> n(-(1 + std::ldexp(T(1), -h - 1)), 1, 1), o(0, 0, 0);
    const ray<T> r{o, d};
    REQUIRE(fm::exact_dot_sign(d, n) == 0);
    REQUIRE_MESSAGE(dot(d, n) != T(0), "stiff: the rounded d.n is not 0");
    // Parallel, one unit off the plane (its point (0, 0, 1)): the plain
    // quotient is a huge positive t, a false hit.
    const vec3<T> off(0, 0, 1);
    REQUIRE(render_kernels::plane_plain(off, n, r) > T(0));
    CHECK(render_kernels::plane_lane(off, n, r, T(0)) == infinity<T>);
    // In the plane (it goes through o + d): num and d.n are the same rounded
    // number, so the plain quotient is 1, a false hit.
    REQUIRE(render_kernels::plane_plain(d, n, r) == T(1));
    CHECK(render_kernels::plane_lane(d, n, r, T(0)) == infinity<T>);
    // Not parallel (the last component 3/2 of the lost term: exact d.n =
    // 2^-(2h+2) > 0): the kernel's t is the plain quotient, bit for bit.
    const vec3<T> d2(d.x, d.y, T(1.5) * d.z);
    REQUIRE(fm::exact_dot_sign(d2, n) == 1);
    const T plain = render_kernels::plane_plain(off, n, ray<T>{o, d2});
    CHECK(render_kernels::plane_lane(off, n, ray<T>{o, d2}, T(0)) == (plain > T(0) ? plain : infinity<T>));
}

TEST_CASE_TEMPLATE("render triangle kernel: in-plane rays and degenerate triangles miss, other answers keep their bits",
                   T, RT_SCALARS) {
    std::mt19937 rng(23);
    int in_plane = 0, degenerate = 0, stiff = 0, plain_false_hits = 0, false_hits = 0;
    for (int i = 0; i < 1000; ++i) {
        const vec3<T> a = full_point<T>(rng), e1 = dyadic<T>(rng), f = dyadic<T>(rng);
        const bool flat = i % 2 == 1;  // degenerate: e2 = 3 e1
        const vec3<T> e2 = flat ? T(3) * e1 : f;
        if (!sum_is_exact(a, e1) || !sum_is_exact(a, e2)) continue;
        vec3<T> o, d;
        if (flat) {  // any ray through the segment's line: aimed at a + 2 e1 (rounded)
            o = full_point<T>(rng) + vec3<T>(0, 0, 2);
            d = (a + T(2) * e1) - o;
        } else {  // in the plane: origin a + e2/2 - e1, direction e1 + e2/4, both exact
            o = a + T(0.5) * e2 - e1;
            d = e1 + T(0.25) * e2;
            if (!sum_is_exact(a, T(0.5) * e2) || !sum_is_exact(a + T(0.5) * e2, -e1) || !sum_is_exact(e1, T(0.25) * e2))
                continue;
        }
        REQUIRE(fm::exact_orientation_sign(d, vec3<T>(0), e1, e2) == 0);
        ++(flat ? degenerate : in_plane);
        stiff += dot(e1, cross(d, e2)) != T(0);
        const ray<T> r{o, d};
        plain_false_hits += render_kernels::triangle_lane(a, e1, e2, r, T(0), false) != infinity<T>;
        false_hits += render_kernels::triangle_lane(a, e1, e2, r, T(0)) != infinity<T>;
    }
    MESSAGE("in plane " << in_plane << ", degenerate " << degenerate << ", rounded determinant not 0 in " << stiff
                        << ", false hits without the exact decision " << plain_false_hits);
    REQUIRE(in_plane >= 100);
    REQUIRE(degenerate >= 100);
    if constexpr (std::is_same_v<T, float>) REQUIRE_MESSAGE(stiff >= 20, "stiff: rounded determinants that are not 0");
    // The family catches the trap: without the decision some of these rays hit.
    CHECK(plain_false_hits > 0);
    CHECK(false_hits == 0);

    // Ordinary triangles and rays: the decision never changes an answer.
    int hits = 0, differ = 0;
    for (int i = 0; i < 2000; ++i) {
        const vec3<T> a = full_point<T>(rng), e1 = full_point<T>(rng) - vec3<T>(T(0.75)),
                      e2 = full_point<T>(rng) - vec3<T>(T(0.75)), o = full_point<T>(rng) + vec3<T>(0, 0, 3);
        const vec3<T> d = (a + T(0.3) * e1 + T(0.3) * e2) - o;
        const ray<T> r{o, d};
        const T with = render_kernels::triangle_lane(a, e1, e2, r, T(0));
        const T without = render_kernels::triangle_lane(a, e1, e2, r, T(0), false);
        hits += with != infinity<T>;
        differ += !(with == without || (std::isnan(with) && std::isnan(without)));
    }
    CHECK(hits > 1000);
    CHECK(differ == 0);
}
TEST_CASE_TEMPLATE("render triangle kernel: a non-zero subnormal direction is a direction (dyadic cases, exact t)", T,
                   RT_SCALARS) {
    // The triangle (-1, -1, h), (3, -1, h), (-1, 3, h) with h = 2^-60, seen from the origin along
    // 2^(low - k) (2^-2, 2^-3, 1) (subnormal components): it crosses z = h at t = 2^(-60 - low + k),
    // at the point (2^-62, 2^-63, h), inside. Every quantity is a power of two, so t is exact.
    const int low = std::numeric_limits<T>::min_exponent;
    const T h = std::ldexp(T(1), -60);
    const vec3<T> a(-1, -1, h), e1(4, 0, 0), e2(0, 4, 0);
    for (int k : {10, 14, std::numeric_limits<T>::digits - 3}) {
        CAPTURE(k);
        const vec3<T> d(std::ldexp(T(1), low - k - 2), std::ldexp(T(1), low - k - 3), std::ldexp(T(1), low - k));
        const T want = std::ldexp(T(1), -60 - low + k);
        REQUIRE(d.x > T(0));
        REQUIRE(std::isfinite(want));
        const T got = render_kernels::triangle_lane(a, e1, e2, ray<T>{vec3<T>(0, 0, 0), d}, T(0));
        CHECK(got == want);
        // Pointing away: a miss, never a NaN.
        CHECK(render_kernels::triangle_lane(a, e1, e2, ray<T>{vec3<T>(0, 0, 0), -d}, T(0)) == infinity<T>);
        // Parallel to the triangle (no z component): a miss.
        CHECK(render_kernels::triangle_lane(a, e1, e2, ray<T>{vec3<T>(0, 0, 0), vec3<T>(d.x, d.y, 0)}, T(0)) ==
              infinity<T>);
        // The plane kernel agrees on the triangle's plane.
        CHECK(render_kernels::plane_lane(a, vec3<T>(0, 0, 1), ray<T>{vec3<T>(0, 0, 0), d}, T(0)) == want);
    }
}
TEST_CASE_TEMPLATE("render plane kernel: a subnormal direction whose d.n loses digits still gives the exact t", T,
                   RT_SCALARS) {
    // The plane x = p (p = 2^(emin + 20)) with normal (1 + 2^-10, 0, 0), seen from the origin along
    // (2^(denorm + 4), 0, 0), denorm the exponent of the smallest subnormal: the product n.d
    // = 2^(denorm + 4) + 2^(denorm - 6) is below the subnormal grid and rounds to 2^(denorm + 4), so
    // num / d.n would be 2^-10 too large (thousands of ULPs). The exact t is p / d_x, a power of two.
    const int emin = std::numeric_limits<T>::min_exponent, denorm = emin - std::numeric_limits<T>::digits;
    const T p = std::ldexp(T(1), emin + 20), dx = std::ldexp(T(1), denorm + 4);
    const vec3<T> n(1 + std::ldexp(T(1), -10), 0, 0), point(p, 0, 0), d(dx, 0, 0);
    const T want = std::ldexp(T(1), emin + 20 - (denorm + 4));
    REQUIRE(std::isfinite(want));
    REQUIRE_MESSAGE(n.x * dx == dx, "stiff: the rounded d.n has lost the 2^-10");
    REQUIRE(render_kernels::plane_plain(point, n, ray<T>{vec3<T>(0, 0, 0), d}) != want);
    CHECK(render_kernels::plane_lane(point, n, ray<T>{vec3<T>(0, 0, 0), d}, T(0)) == want);
    CHECK(plane_lane_scene(point, n, ray<T>{vec3<T>(0, 0, 0), d}, T(0)) == want);
    // Pointing away: a miss.
    CHECK(render_kernels::plane_lane(point, n, ray<T>{vec3<T>(0, 0, 0), -d}, T(0)) == infinity<T>);
}

TEST_CASE_TEMPLATE("render triangle kernel: rays exactly in a triangle's plane miss even where its edges round", T,
                   RT_SCALARS) {
    // Corner a = K u is coarse (K = 2^(digits + 3)), b = v and c = v + m are small integers: the edges
    // b - a and c - a round in T, so the rounded edges need not span the plane any more. The ray runs
    // along the edge bc (origin v - k m, direction m, all exact): it lies in the triangle's plane.
    std::mt19937 rng(41);
    std::uniform_int_distribution<int> small(-7, 7), mid(-(1 << 10), 1 << 10), steps(1, 4);
    const T K = std::ldexp(T(1), std::numeric_limits<T>::digits + 3);
    int cases = 0, edges_not_flat = 0, false_hits = 0;
    for (int i = 0; i < 400; ++i) {
        const vec3<T> u(T(small(rng)), T(small(rng)), T(small(rng))), v(T(mid(rng)), T(mid(rng)), T(mid(rng))),
            m(T(small(rng)), T(small(rng)), T(small(rng)));
        if (u == vec3<T>(0, 0, 0) || m == vec3<T>(0, 0, 0)) continue;
        const vec3<T> a = K * u, b = v, c = v + m;
        const ray<T> r{v - T(steps(rng)) * m, m};
        REQUIRE(fm::exact_orientation_sign(r.direction, a, b, c) == 0);
        ++cases;
        edges_not_flat += fm::exact_orientation_sign(r.direction, vec3<T>(0), b - a, c - a) != 0;
        for (const interval<T> range : {interval<T>{T(0), infinity<T>}, interval<T>{-infinity<T>, infinity<T>}})
            false_hits += render_kernels::triangle_lane_corners(a, b, c, r, range.min) < range.max;
    }
    MESSAGE(cases << " in-plane rays, rounded edges not flat in " << edges_not_flat);
    REQUIRE(cases >= 300);
    REQUIRE_MESSAGE(edges_not_flat >= 30, "stiff: rounded edges that are not flat");
    CHECK(false_hits == 0);
}
#endif
