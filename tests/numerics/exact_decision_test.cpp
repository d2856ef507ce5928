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
    return fm::two_sum(x, y).lo == 0 && std::isfinite(x + y);
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
