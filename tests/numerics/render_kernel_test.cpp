// The renderer's lane loops (tools/render/fast_path_*.hpp) on held-out
// style cases of issue 23 with exact references: directions whose d.d
// underflows (promise 1), the brute-force triangle loop's cull on tiny
// triangles (promise 2), and the slab test with the origin on a face plane
// and a zero direction component, at coordinates near 2^-100 (promise 3).
//
// The parts of fast_path.cpp are compiled here as they are there (in a
// namespace of their own, for plain x86-64), so the tests call the very
// closest_hits, any_hit and tree walks the renderer runs.
#if __has_include("fast_path_kernels.hpp")
#include "numerics_support.hpp"
#include "reference.hpp"

#include "bvh_build.hpp"
#include "fast_path.hpp"
#include "fast_path_kernels.hpp"

#include "common/render.hpp"
#include "common/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

namespace rt::render_tool::isa_test {
namespace {
#define RT_FAST_PATH_PARTS 1
#include "fast_path_arrays.hpp"
#include "fast_path_traversal.hpp"
#include "fast_path_spheres.hpp"
#include "fast_path_planes.hpp"
#include "fast_path_triangles.hpp"
#include "fast_path_queries.hpp"
#undef RT_FAST_PATH_PARTS
}  // namespace
}  // namespace rt::render_tool::isa_test

using namespace rt;
using namespace rt::render_tool;  // bvh_box, build_bvh, collapse_to_wide
namespace rk = rt::render_tool::isa_test;

namespace {

// A few unit-ish spheres in front of the origin, at coordinates T holds exactly.
template <class T>
scene<double> sphere_scene() {
    scene<double> s;
    s.materials.push_back(material{});
    const double place[][4] = {{0, 0, -5, 1}, {1.5, 0.25, -7, 0.75}, {-1.25, -0.5, -6, 0.5}};
    for (const auto& p : place) s.spheres.push_back(sphere<double>{vec3d(p[0], p[1], p[2]), p[3], 0});
    return s;
}

template <class T>
sphere<T> sphere_in(const scene<double>& s, size_t i) {
    return sphere<T>{convert<T>(s.spheres[i].center), T(s.spheres[i].radius), 0};
}

// Directions at the spheres' centres with a random offset, then multiplied
// by a tiny factor that is not a power of two (each component rounds), so
// that |d| is about 1e-20 in float: normal components whose d.d = 1e-40 is
// below float's normal range, and 1 / d.d overflows; about 1e-170 in double.
template <class T>
std::vector<vec3<T>> tiny_directions(const scene<double>& s, int count) {
    const T tiny = std::is_same_v<T, float> ? T(1.7e-21) : T(1.7e-171);
    std::mt19937 rng(2023);
    std::uniform_real_distribution<double> jitter(-0.6, 0.6);
    std::vector<vec3<T>> out;
    for (int i = 0; i < count; ++i) {
        const sphere<double>& x = s.spheres[size_t(i) % s.spheres.size()];
        const vec3d aim = x.center + x.radius * vec3d(jitter(rng), jitter(rng), 0);
        out.push_back(convert<T>(aim) * tiny);
    }
    return out;
}

// The nearest reference crossing of the ray with any sphere in (tmin, inf).
template <class T>
study::reference_answer nearest_reference(const scene<double>& s, const ray<T>& r, T tmin) {
    study::reference_answer best;
    for (size_t i = 0; i < s.spheres.size(); ++i) {
        const auto a = study::sphere_reference(r, sphere_in<T>(s, i), interval<T>{tmin, infinity<T>});
        if (a.hit && (!best.hit || a.t < best.t)) best = a;
    }
    return best;
}

template <class T, rk::sphere_mode SM>
void check_tiny_directions() {
    const scene<double> world = sphere_scene<T>();
    const rk::soa_scene<T> soa(world, false, 8.0);
    const std::vector<vec3<T>> dirs = tiny_directions<T>(world, 4 * rk::W);
    const T tmin = 0;
    int hits = 0, wrong_closest = 0, wrong_any = 0;
    double worst = 0;
    for (size_t g = 0; g < dirs.size(); g += rk::W) {
        rk::packet<T> p;
        for (int k = 0; k < rk::W; ++k) {
            p.ox[k] = p.oy[k] = p.oz[k] = 0;
            p.dx[k] = dirs[g + size_t(k)].x, p.dy[k] = dirs[g + size_t(k)].y, p.dz[k] = dirs[g + size_t(k)].z;
        }
        alignas(64) T t[rk::W];
        alignas(64) rk::index_t<T> object[rk::W];
        rk::closest_hits<T, SM, true>(soa, p, tmin, t, object);
        for (int k = 0; k < rk::W; ++k) {
            const ray<T> r{vec3<T>(0, 0, 0), dirs[g + size_t(k)]};
            const study::reference_answer ref = nearest_reference(world, r, tmin);
            hits += ref.hit;
            if ((object[k] >= 0) != ref.hit) {
                ++wrong_closest;
                continue;
            }
            if (ref.hit) worst = std::max(worst, double(std::fabs((long double)t[k] - ref.t) / ref.t));
            // Any hit: blocked before twice the crossing, free before half of it.
            const T full = ref.hit ? T(2 * ref.t) : infinity<T>, half = ref.hit ? T(ref.t / 2) : infinity<T>;
            if (rk::any_hit<T, SM>(soa, r, tmin, full) != ref.hit) ++wrong_any;
            if (ref.hit && rk::any_hit<T, SM>(soa, r, tmin, half)) ++wrong_any;
        }
    }
    INFO("hits in the reference: " << hits << " of " << dirs.size());
    CHECK(hits > int(dirs.size()) / 2);  // the family is what it says: mostly hits
    CHECK(wrong_closest == 0);
    CHECK(wrong_any == 0);
    CHECK(worst < 1e-3);  // plain float on these well-conditioned spheres: about 1e-6
}

TEST_CASE_TEMPLATE("render sphere kernels: a direction 1e-20 long (float; 1e-170 in double) finds every hit, closest and any",
                   T, float, double) {
    SUBCASE("plain") { check_tiny_directions<T, rk::sphere_mode::plain>(); }
    SUBCASE("robust") { check_tiny_directions<T, rk::sphere_mode::robust>(); }
}

// Tiny triangles (1e-4 across) 1000 units away, float: the cull's rounding
// of the ray's distance from a triangle (about 11 u |f| = 7e-4) is larger
// than the triangle. Brute force (with the cull) and the tree (boxes, no
// cull) must give the same t and object for every ray, bit for bit.
TEST_CASE("render brute-force triangle cull: tiny far triangles give brute force's answer = the tree's, bit for bit") {
    using T = float;
    scene<double> world;
    world.materials.push_back(material{});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> spread(-40, 40), corner(-1e-4, 1e-4);
    for (int i = 0; i < 24; ++i) {
        const vec3d c(spread(rng), spread(rng), -1000.0);
        auto at = [&] { return convert<double>(convert<T>(c + vec3d(corner(rng), corner(rng), corner(rng)))); };
        world.triangles.push_back(triangle<double>{at(), at(), at(), 0});
    }
    const rk::soa_scene<T> brute(world, false, 1000.0), tree(world, true, 1000.0);
    std::uniform_real_distribution<double> aim(-2e-5, 2e-5);
    int hits = 0, differ = 0;
    for (int g = 0; g < 48; ++g) {
        rk::packet<T> p;
        for (int k = 0; k < rk::W; ++k) {
            const triangle<double>& x = world.triangles[size_t(g * rk::W + k) % world.triangles.size()];
            const vec3d target = (x.a + x.b + x.c) / 3.0 + vec3d(aim(rng), aim(rng), 0);
            p.ox[k] = p.oy[k] = p.oz[k] = 0;
            p.dx[k] = T(target.x / 1000), p.dy[k] = T(target.y / 1000), p.dz[k] = T(-1);
        }
        alignas(64) T tb[rk::W], tt[rk::W];
        alignas(64) rk::index_t<T> ob[rk::W], ot[rk::W];
        rk::closest_hits<T, rk::sphere_mode::robust, true>(brute, p, T(0), tb, ob);
        rk::closest_hits<T, rk::sphere_mode::robust, true>(tree, p, T(0), tt, ot);
        for (int k = 0; k < rk::W; ++k) {
            hits += ot[k] >= 0;
            differ += ob[k] != ot[k] || std::memcmp(&tb[k], &tt[k], sizeof(T)) != 0;
        }
    }
    INFO("tree hits: " << hits << " of " << 48 * rk::W);
    CHECK(hits > 200);
    CHECK(differ == 0);
}

// One box, [2^-100, 2^-99]^3 in float, as a one-leaf tree, walked by one
// ray's walk (closest hits of triangles, shadow rays) and by the packet
// walk (every lane the same ray). Chapter 08's rule: a ray parallel to a slab, with its origin
// on one of the slab's face planes, lies in the closed slab for every t.
struct box_case {
    float o[3], d[3];
    bool crosses;  // the exact answer: does the ray meet the closed box at some t in [0, 10)?
};

std::vector<box_case> box_cases() {
    const float lo = 0x1p-100f, hi = 0x1p-99f, mid = 0x1.8p-100f;
    return {
        // origin on the high x face, running along it (d.x = 0) towards the box from below in z
        {{hi, mid, -1}, {0, 0, 1}, true},
        {{lo, mid, -1}, {0, 0, 1}, true},
        {{hi, hi, -1}, {0, 0, 1}, true},    // along an edge
        {{hi, mid, -1}, {-0.0f, 0, 1}, true},  // d.x = -0: its reciprocal is -inf
        {{mid, mid, -1}, {0, 0, 1}, true},  // inside the x and y slabs: the exit must not be near t = 1
        {{mid, mid, -1}, {0, 0, 0.25f}, true},
        {{hi + 0x1p-120f, mid, -1}, {0, 0, 1}, false},  // just outside the x slab
        {{mid, mid, 1}, {0, 0, 1}, false},               // moving away
    };
}

TEST_CASE("render box test: origin on a face plane, a zero direction component, coordinates near 2^-100 (float)") {
    const std::vector<box_case> cases = box_cases();
    const float lo = 0x1p-100f, hi = 0x1p-99f;
    bvh_box box{{lo, lo, lo}, {hi, hi, hi}};
    const bvh_wide_tree wide_tree = collapse_to_wide(build_bvh({box, box}));  // two boxes: a root with two leaves
    for (const box_case& c : cases) {
        INFO("origin (" << c.o[0] << ", " << c.o[1] << ", " << c.o[2] << "), direction (" << c.d[0] << ", " << c.d[1]
                        << ", " << c.d[2] << ")");
        // one ray's walk
        const float origin[3] = {c.o[0], c.o[1], c.o[2]}, direction[3] = {c.d[0], c.d[1], c.d[2]};
        CHECK(rk::traverse_wide<true>(wide_tree, origin, direction, 10.0f,
                                      [](std::uint32_t, std::uint32_t) { return true; }) == c.crosses);
        // the packet walk (primary rays)
        rk::packet<float> p;
        alignas(64) float best_t[rk::W];
        for (int k = 0; k < rk::W; ++k) {
            p.ox[k] = c.o[0], p.oy[k] = c.o[1], p.oz[k] = c.o[2];
            p.dx[k] = c.d[0], p.dy[k] = c.d[1], p.dz[k] = c.d[2];
            best_t[k] = 10.0f;
        }
        bool leaf_reached = false;
        rk::traverse_packet(wide_tree, p, best_t, [&](size_t, size_t) { leaf_reached = true; },
                            [&](int, size_t, size_t) { leaf_reached = true; });
        CHECK(leaf_reached == c.crosses);
        // ... and with only lane 5 carrying the case (the others move away
        // from the box), which the packet walk hands to that ray alone
        // (traverse_wide from the leaf): the same rule there.
        for (int k = 0; k < rk::W; ++k)
            if (k != 5) p.ox[k] = p.oy[k] = 0x1.8p-100f, p.oz[k] = 1, p.dx[k] = p.dy[k] = 0, p.dz[k] = 1;
        int whole = 0, alone = 0;
        rk::traverse_packet(wide_tree, p, best_t, [&](size_t, size_t) { ++whole; }, [&](int k, size_t, size_t) { alone += k == 5 ? 1 : 100; });
        CHECK(whole == 0);
        CHECK((alone > 0) == c.crosses);
        CHECK(alone < 100);
    }
}

}  // namespace
#endif

TEST_CASE("render box corners: float_at_or_below is the largest float at or below x, float_at_or_above the smallest at or above") {
    // The trees' boxes are rounded outwards with these (float_box_around):
    // a corner on the wrong side of the double box drops hits, one a step
    // too far out only costs a little. Checked on random bit patterns (every
    // exponent), on small and large magnitudes, subnormals, zeros, the ends
    // of float's range and the infinities.
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-10, 10);
    std::vector<double> xs = {0.0, -0.0, 1e-46, -1e-46, 1e-45, -1e-45, 1.401298464324817e-45, 3.4028234663852886e38,
                              -3.4028234663852886e38, 3.4028235677973366e38, 1e39, -1e39,
                              std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (int i = 0; i < 200000; ++i) {
        const std::uint64_t bits = rng();
        double x;
        std::memcpy(&x, &bits, sizeof x);
        if (!std::isnan(x)) xs.push_back(x);
        xs.push_back(u(rng)), xs.push_back(u(rng) * 1e-40), xs.push_back(std::ldexp(u(rng), -149)), xs.push_back(u(rng) * 1e38);
    }
    const float inf = std::numeric_limits<float>::infinity();
    size_t wrong_side = 0, loose = 0;
    for (double x : xs) {
        const float below = float_at_or_below(x), above = float_at_or_above(x);
        wrong_side += !(double(below) <= x) + !(double(above) >= x);
        // Tight: the next float out is past x (or x lies beyond float's range).
        loose += !(double(std::nextafter(below, inf)) > x) && below != inf;
        loose += !(double(std::nextafter(above, -inf)) < x) && above != -inf;
    }
    CHECK(wrong_side == 0);
    CHECK(loose == 0);
    CHECK(std::signbit(float_at_or_below(0.0)) == false);  // zero is a float: kept as it is
    CHECK(float_at_or_below(1e-300) == 0.0f);
    CHECK(float_at_or_above(1e-300) == std::numeric_limits<float>::denorm_min());
}
