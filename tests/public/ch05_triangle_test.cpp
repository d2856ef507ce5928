// Public tests for chapter 05: a ray against a triangle.
//
// Each case is one idea from the lecture. When a check fails, its message
// names that idea; the numbers follow.
//
// Most cases use the triangle a = (0,0,0), b = (2,0,0), c = (0,2,0) in the
// plane z = 0 (normal (b - a) x (c - a) = (0,0,4), pointing to +z), hit by
// rays coming straight down from z = 3, so every hit has t = 3.
#include "05-triangle/triangle.hpp"

#include "test_support.hpp"

#include <cmath>

using namespace rt;
using rt::ch05::barycentric;
using rt::ch05::intersect_triangle;
using rt::test::close;
using rt::test::describe;
using rt::test::describe_hit;
using rt::test::everything_ahead;

namespace {

template <class T>
triangle<T> corner_triangle() {
    return {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0};
}

// A ray from height 3 straight down onto the point (x, y, 0).
template <class T>
ray<T> down_onto(T x, T y) {
    return {{x, y, 3}, {0, 0, -1}};
}


}  // namespace

TEST_CASE_TEMPLATE("a ray through the inside of the triangle hits it", T, RT_SCALARS) {
    auto hit = intersect_triangle(corner_triangle<T>(), down_onto(T(0.5), T(0.5)), everything_ahead<T>());
    // On a miss, find out which edge test is at fault: a ray just past an edge that comes back as a hit
    // means that edge's test accepts its outer side.
    std::string which_edge;
    if (!hit) {
        const char* edges[] = {"a -> b", "b -> c", "c -> a"};
        const T past[][2] = {{1, T(-0.5)}, {T(1.5), T(1.5)}, {T(-0.5), 1}};
        const char* past_names[] = {"(1, -0.5, 0)", "(1.5, 1.5, 0)", "(-0.5, 1, 0)"};
        for (int e = 0; e < 3; ++e)
            if (intersect_triangle(corner_triangle<T>(), down_onto(past[e][0], past[e][1]), everything_ahead<T>()))
                which_edge += std::string(" The ray onto ") + past_names[e] + ", OUTSIDE edge " + edges[e] + ", is a hit: that edge's half-plane test is "
                              "reversed (its inequality, or the order of its cross product), so it keeps the outer "
                              "side and rejects the inner one.";
    }
    REQUIRE_MESSAGE(hit.has_value(),
                    "(0.5, 0.5, 0) is inside the triangle: the plane hit is on the inner side of all three "
                    "edges, so it is a hit; got a miss."
                        << which_edge);
    CHECK_MESSAGE(close(hit->t, T(3)), "the ray falls from z = 3 onto the plane z = 0: t = 3; got "
                                           << describe_hit(hit));
    CHECK_MESSAGE((close(hit->point.x, T(0.5)) && close(hit->point.y, T(0.5)) && close(hit->point.z, T(0), T(1))),
                  "the hit point is r(t) = (0.5, 0.5, 0); got " << describe_hit(hit));
    CHECK_MESSAGE((close(length(hit->normal), T(1)) && close(hit->normal.z, T(1))),
                  "the normal is (b - a) x (c - a) normalised, (0, 0, 1); got "
                      << describe_hit(hit));
}

TEST_CASE_TEMPLATE("a ray past any one edge misses the triangle", T, RT_SCALARS) {
    const triangle<T> tri = corner_triangle<T>();
    auto past_ab = intersect_triangle(tri, down_onto(T(1), T(-0.5)), everything_ahead<T>());
    CHECK_MESSAGE(!past_ab.has_value(),
                  "(1, -0.5, 0) is on the plane but on the outer side of edge a -> b (below y = 0), so the "
                  "edge test (b - a) x (p - a) . n >= 0 fails: a miss. Got "
                      << describe_hit(past_ab));
    auto past_bc = intersect_triangle(tri, down_onto(T(1.5), T(1.5)), everything_ahead<T>());
    CHECK_MESSAGE(!past_bc.has_value(),
                  "(1.5, 1.5, 0) is on the outer side of edge b -> c (beyond x + y = 2), so the edge test "
                  "(c - b) x (p - b) . n >= 0 fails: a miss. Got "
                      << describe_hit(past_bc));
    auto past_ca = intersect_triangle(tri, down_onto(T(-0.5), T(1)), everything_ahead<T>());
    CHECK_MESSAGE(!past_ca.has_value(),
                  "(-0.5, 1, 0) is on the outer side of edge c -> a (left of x = 0), so the edge test "
                  "(a - c) x (p - c) . n >= 0 fails: a miss. Got "
                      << describe_hit(past_ca));
}

TEST_CASE_TEMPLATE("points on an edge or a corner count as inside", T, RT_SCALARS) {
    const triangle<T> tri = corner_triangle<T>();
    const T points[][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}, {2, 0}, {0, 2}};
    const std::string names[] = {"the middle of edge a -> b", "the middle of edge b -> c", "the middle of edge c -> a",
                           "corner a",                  "corner b",                  "corner c"};
    for (int i = 0; i < 6; ++i) {
        auto hit = intersect_triangle(tri, down_onto(points[i][0], points[i][1]), everything_ahead<T>());
        CHECK_MESSAGE((hit.has_value() && close(hit->t, T(3))),
                      "a ray onto " << names[i] << " (" << points[i][0] << ", " << points[i][1]
                                    << ", 0) must hit at t = 3: edges and corners belong to the triangle, so the "
                                       "edge tests are >= 0, not > 0. Got "
                                    << describe_hit(hit));
    }
}

TEST_CASE_TEMPLATE("barycentric coordinates sum to 1 and rebuild the point", T, RT_SCALARS) {
    const triangle<T> tri{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0};
    // p = 0.2 a + 0.3 b + 0.5 c lies in the triangle's plane x + y + z = 1.
    const vec3<T> p{T(0.2), T(0.3), T(0.5)};
    const vec3<T> w = barycentric(tri, p);
    CHECK_MESSAGE(close(w.x + w.y + w.z, T(1)),
                  "alpha + beta + gamma must be 1 (each is a sub-triangle's area over the whole area); got "
                      << describe(w));
    CHECK_MESSAGE((close(w.x, T(0.2)) && close(w.y, T(0.3)) && close(w.z, T(0.5))),
                  "p = 0.2 a + 0.3 b + 0.5 c, so (alpha, beta, gamma) = (0.2, 0.3, 0.5), in the order of the "
                  "corners a, b, c; got "
                      << describe(w));
    const vec3<T> rebuilt = w.x * tri.a + w.y * tri.b + w.z * tri.c;
    CHECK_MESSAGE((close(rebuilt.x, p.x) && close(rebuilt.y, p.y) && close(rebuilt.z, p.z)),
                  "alpha a + beta b + gamma c must give back the point " << describe(p) << "; got "
                                                                          << describe(rebuilt));
    const vec3<T> at_b = barycentric(tri, tri.b);
    CHECK_MESSAGE((close(at_b.x, T(0), T(1)) && close(at_b.y, T(1)) && close(at_b.z, T(0), T(1))),
                  "at corner b the coordinates are (0, 1, 0); got " << describe(at_b));
}

TEST_CASE_TEMPLATE("the shared diagonal of a quad is hit by at least one of its triangles", T, RT_SCALARS) {
    // The square (0,0)-(2,0)-(2,2)-(0,2) cut along its diagonal from (0,0) to (2,2).
    const triangle<T> lower{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, 0};
    const triangle<T> upper{{0, 0, 0}, {2, 2, 0}, {0, 2, 0}, 0};
    for (T s : {T(0.25), T(0.5), T(1), T(1.5), T(1.75)}) {
        const ray<T> r = down_onto(s, s);
        const bool seen = intersect_triangle(lower, r, everything_ahead<T>()).has_value() ||
                          intersect_triangle(upper, r, everything_ahead<T>()).has_value();
        CHECK_MESSAGE(seen, "a ray onto the diagonal point (" << s << ", " << s
                                                               << ", 0) hit neither triangle: a crack between two "
                                                                  "triangles that share an edge. A point on an "
                                                                  "edge must pass the edge test (>= 0, not > 0)");
    }
}

TEST_CASE_TEMPLATE("a degenerate triangle is a miss", T, RT_SCALARS) {
    // Three corners on one line: zero area, (b - a) x (c - a) = 0, no plane to hit.
    const triangle<T> line{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, 0};
    auto hit = intersect_triangle(line, down_onto(T(1), T(1)), everything_ahead<T>());
    CHECK_MESSAGE(!hit.has_value(),
                  "corners on one line make a triangle of zero area: its normal is the zero vector, and the "
                  "contract calls it a miss (never a NaN hit); got "
                      << describe_hit(hit));
    const triangle<T> point{{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, 0};
    auto hit_point = intersect_triangle(point, down_onto(T(1), T(1)), everything_ahead<T>());
    CHECK_MESSAGE(!hit_point.has_value(),
                  "a triangle whose three corners coincide has zero area: a miss; got " << describe_hit(hit_point));
    const vec3<T> w = barycentric(line, vec3<T>{1, 1, 0});
    CHECK_MESSAGE((std::isnan(w.x) && std::isnan(w.y) && std::isnan(w.z)),
                  "barycentric coordinates of a zero-area triangle do not exist (the areas are divided by "
                  "zero): the contract asks for NaN in all three; got "
                      << describe(w));
}

TEST_CASE_TEMPLATE("a ray parallel to the triangle misses it", T, RT_SCALARS) {
    // Sideways at height 1 above the triangle, and sideways inside its plane.
    auto above = intersect_triangle(corner_triangle<T>(), ray<T>{{-1, T(0.5), 1}, {1, 0, 0}}, everything_ahead<T>());
    CHECK_MESSAGE(!above.has_value(),
                  "d . n = 0: the ray runs parallel to the triangle's plane and never reaches it; got "
                      << describe_hit(above));
    auto inside = intersect_triangle(corner_triangle<T>(), ray<T>{{-1, T(0.5), 0}, {1, 0, 0}}, everything_ahead<T>());
    CHECK_MESSAGE(!inside.has_value(),
                  "a ray lying in the triangle's plane has d . n = 0 and (a - o) . n = 0, so t = 0 / 0: test "
                  "d . n before dividing; the contract calls it a miss. Got "
                      << describe_hit(inside));
}

TEST_CASE_TEMPLATE("the triangle normal follows its winding and a ray from behind sees the back face", T,
                   RT_SCALARS) {
    // From below (z = -3 going up): the normal (0, 0, 1) points away from this ray. The hit still
    // reports (0, 0, 1); the one face rule (common/hit_record.hpp) says the ray sees the back face
    // and gives the normal on the ray's side, (0, 0, -1), for shading.
    const ray<T> r{{T(0.5), T(0.5), -3}, {0, 0, 1}};
    auto hit = intersect_triangle(corner_triangle<T>(), r, everything_ahead<T>());
    REQUIRE_MESSAGE(hit.has_value(), "a triangle can be hit from either side; got a miss from below");
    CHECK_MESSAGE(close(hit->normal.z, T(1)),
                  "the normal is (b - a) x (c - a) normalised, (0, 0, 1), from either side: do not turn it "
                  "towards the ray (hit.facing_normal(r) does that, once, for every shape). Got "
                      << describe_hit(hit));
    CHECK_MESSAGE(close(length(hit->normal), T(1)),
                  "the normal must be unit length ((b - a) x (c - a) has length twice the area); got "
                      << describe_hit(hit));
    CHECK_MESSAGE(!hit->front_face(r), "a ray from below sees the triangle's back face: front_face(r) is false");
    CHECK_MESSAGE(close(hit->facing_normal(r).z, T(-1)),
                  "seen from below, the normal on the ray's side is (0, 0, -1); got " << describe_hit(hit));
    // The winding decides the outward side: the same corners listed the other way round.
    const triangle<T> reversed{{0, 0, 0}, {0, 2, 0}, {2, 0, 0}, 0};
    auto back = intersect_triangle(reversed, r, everything_ahead<T>());
    REQUIRE_MESSAGE(back.has_value(), "the corners a, c, b make the same triangle: a hit; got a miss");
    CHECK_MESSAGE(close(back->normal.z, T(-1)),
                  "with the corners in the other order, (b - a) x (c - a) = (0, 0, -4): the normal is (0, 0, -1), "
                  "and this ray from below sees a front face; got "
                      << describe_hit(back));
}

TEST_CASE_TEMPLATE("triangle hits outside (tmin tmax) do not count", T, RT_SCALARS) {
    const triangle<T> tri = corner_triangle<T>();
    const ray<T> r = down_onto(T(0.5), T(0.5));  // hit at t = 3
    auto too_far = intersect_triangle(tri, r, interval<T>{T(0), T(2)});
    CHECK_MESSAGE(!too_far.has_value(), "the hit at t = 3 is beyond tmax = 2; got " << describe_hit(too_far));
    auto too_near = intersect_triangle(tri, r, interval<T>{T(4), T(10)});
    CHECK_MESSAGE(!too_near.has_value(), "the hit at t = 3 is before tmin = 4; got " << describe_hit(too_near));
    auto behind = intersect_triangle(tri, ray<T>{{T(0.5), T(0.5), 3}, {0, 0, 1}}, everything_ahead<T>());
    CHECK_MESSAGE(!behind.has_value(),
                  "going up from z = 3, the triangle is behind the ray (t = -3 < tmin = 0); got "
                      << describe_hit(behind));
    auto inside = intersect_triangle(tri, r, interval<T>{T(1), T(5)});
    CHECK_MESSAGE((inside.has_value() && close(inside->t, T(3))),
                  "t = 3 lies inside (1, 5), so it is a hit; got " << describe_hit(inside));
}

TEST_CASE_TEMPLATE("very small and very large triangles are hit like unit ones", T, RT_SCALARS) {
    // Edges of 2^-40 and 2^40 (float) or 2^-270 and 2^270 (double): edge^4 under- or overflows T.
    const int e = sizeof(T) == 4 ? 40 : 270;
    for (int sign : {-1, 1}) {
        const T size = std::ldexp(T(1), sign * e);
        const triangle<T> tri{{0, 0, 0}, {2 * size, 0, 0}, {0, 2 * size, 0}, 0};
        auto inside = intersect_triangle(tri, ray<T>{{size / 2, size / 2, size}, {0, 0, -size}}, everything_ahead<T>());
        REQUIRE_MESSAGE(inside.has_value(), "a triangle with edges " << double(2 * size) << " long: the ray through "
                                            "(0.25, 0.25) of it must hit. n . n = edge^4 = " << double(size) * double(size) * 16
                                            << " leaves T's range: scale the edges by a power of two first (std::ilogb, "
                                               "std::ldexp). Got a miss");
        CHECK_MESSAGE(close(inside->t, T(1)), "the hit is at t = 1; got " << describe_hit(inside));
        CHECK_MESSAGE(rt::test::is_unit(inside->normal), "the unit normal must not under- or overflow; got " << describe_hit(inside));
        const vec3<T> w = barycentric(tri, vec3<T>{size / 2, size, 0});
        CHECK_MESSAGE((close(w.x, T(0.25)) && close(w.y, T(0.25)) && close(w.z, T(0.5))),
                      "barycentric coordinates do not depend on the size: (0.25, 0.25, 0.5); got " << describe(w));
    }
}
