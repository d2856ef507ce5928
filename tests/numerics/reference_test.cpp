// The references themselves: MPFR answers checked against cases solved by
// hand, and against a long double computation on well-conditioned cases.
// Every error in the study is measured against these, so they are tested
// first.
#include "numerics_support.hpp"

using namespace rt;
using namespace rt::numerics_test;

TEST_CASE_TEMPLATE("sphere reference gives the hand-solved roots", T, RT_SCALARS) {
    sphere<T> unit{};
    interval<T> ahead{T(0), infinity<T>};
    // From z = 5 towards the origin: the crossings are t = 4 and t = 6.
    reference_answer r = sphere_reference<T>({{0, 0, 5}, {0, 0, -1}}, unit, ahead);
    CHECK(r.hit);
    CHECK(r.t == 4);
    CHECK(r.t_far == 6);
    // Tangent at (0, 1, 0): one double root, t = 5, a hit.
    r = sphere_reference<T>({{0, 1, 5}, {0, 0, -1}}, unit, ahead);
    CHECK(r.hit);
    CHECK(r.t == 5);
    // One ULP above the tangent: a miss, however close.
    r = sphere_reference<T>({{0, std::nextafter(T(1), T(2)), 5}, {0, 0, -1}}, unit, ahead);
    CHECK_FALSE(r.hit);
    // The range is open: roots exactly at tmin and tmax do not count.
    r = sphere_reference<T>({{0, 0, 5}, {0, 0, -1}}, unit, {T(4), T(6)});
    CHECK_FALSE(r.hit);
    // Invalid input is a miss.
    r = sphere_reference<T>({{0, 0, 5}, {0, 0, 0}}, unit, ahead);
    CHECK_FALSE(r.hit);
}

TEST_CASE_TEMPLATE("triangle and plane references count edges as inside", T, RT_SCALARS) {
    triangle<T> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0};
    interval<T> ahead{T(0), infinity<T>};
    // Through the middle of the edge from b to c, and through corner a.
    CHECK(triangle_reference<T>({{T(0.5), T(0.5), 1}, {0, 0, -1}}, tri, ahead).hit);
    CHECK(triangle_reference<T>({{0, 0, 1}, {0, 0, -1}}, tri, ahead).hit);
    CHECK_FALSE(triangle_reference<T>({{T(0.75), T(0.75), 1}, {0, 0, -1}}, tri, ahead).hit);
    CHECK(triangle_reference<T>({{T(0.25), T(0.25), 3}, {0, 0, -1}}, tri, ahead).t == 3);
    plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    CHECK(plane_reference<T>({{0, 2, 0}, {1, -1, 0}}, ground, ahead).t == 2);
    CHECK_FALSE(plane_reference<T>({{0, 2, 0}, {1, 0, 0}}, ground, ahead).hit);
}

TEST_CASE("sphere reference agrees with long double on well-conditioned cases") {
    auto fam = well_sphere_family<double>(small_cases());
    auto refs = references(fam);
    std::size_t checked = 0, disagree = 0;
    for (std::size_t i = 0; i < fam.queries.size(); ++i) {
        const auto& q = fam.queries[i];
        using L = long double;
        L fx = L(q.r.origin.x) - q.shape.center.x, fy = L(q.r.origin.y) - q.shape.center.y,
          fz = L(q.r.origin.z) - q.shape.center.z;
        L dx = q.r.direction.x, dy = q.r.direction.y, dz = q.r.direction.z;
        L a = dx * dx + dy * dy + dz * dz, h = fx * dx + fy * dy + fz * dz;
        L c = fx * fx + fy * fy + fz * fz - L(q.shape.radius) * q.shape.radius;
        L disc = h * h - a * c;
        if (!(disc > 0) || !refs[i].hit) continue;
        L qq = -(h + std::copysign(std::sqrt(disc), h));
        L t0 = std::min(c / qq, qq / a);
        if (t0 <= 0) continue;  // origin inside: the far root; skip for simplicity
        ++checked;
        disagree += std::fabs(t0 - refs[i].t) > 1e-12L * std::fabs(t0);
    }
    REQUIRE(checked > 100);
    CHECK_MESSAGE(disagree == 0, disagree << " of " << checked << " MPFR roots differ from long double beyond 1e-12");
}
