// Public tests for chapter 09, exercise 2: where a secondary ray starts
// (offset_ray_origin, spawn.hpp).
//
// The stiff cases (ch09_cases.hpp) are points on surfaces where rounding
// hurts, each with its error bound (surface_error.hpp). Whether a spawned
// ray would re-hit its surface is decided exactly, by the side of the exact
// surface its origin lies on (ch09_exact.hpp), not by an intersection
// routine with rounding of its own.
#include "09-reflection/optics.hpp"
#include "09-reflection/spawn.hpp"
#include "02-sphere/sphere.hpp"

#include "ch09_cases.hpp"
#include "test_support.hpp"

#include <cmath>
#include <map>
#include <string>

using namespace rt;
using rt::ch09::offset_ray_origin;
using rt::ch09::surface_point;
using rt::test::describe;

namespace {

// The mirror direction, written here (not your reflect) so these tests are
// about the offset only.
template <class T>
vec3<T> mirror(const vec3<T>& d, const vec3<T>& n) {
    return d - T(2) * dot(d, n) * n;
}

}  // namespace

TEST_CASE_TEMPLATE("spawn: the origin moves along the normal, not along the ray", T, RT_SCALARS) {
    const surface_point<T> p{{T(1), T(2), T(3)}, {T(1e-3), T(2e-3), T(3e-3)}};
    const vec3<T> n = normalize(vec3<T>(1, 1, 0));
    const vec3<T> w = normalize(vec3<T>(1, T(0.2), T(0.5)));  // leaves on n's side, far from n's direction
    const vec3<T> o = offset_ray_origin(p, n, w);
    const vec3<T> moved = o - p.point;
    CAPTURE(describe(o));
    CHECK_MESSAGE(std::fabs(moved.z) <= T(1e-6),
                  "the normal (1, 1, 0) / sqrt(2) has no z part, so the origin must not move in z (push along n, not w)");
    CHECK_MESSAGE(std::fabs(moved.x - moved.y) <= T(1e-6), "along n = (1, 1, 0) / sqrt(2), x and y move alike");
    // dot(|n|, error) = (1e-3 + 2e-3) / sqrt(2).
    const T reach = T(3e-3) / std::sqrt(T(2));
    CHECK_MESSAGE(std::fabs(dot(moved, n) - reach) <= T(1e-5) * reach + T(2) * rt::test::float_steps_along(o, n),
                  "the distance moved is dot(|n|, error) = " << reach << "; moved " << dot(moved, n));
}

TEST_CASE_TEMPLATE("spawn: a reflected ray starts on the side it leaves by, a refracted one on the far side", T,
                   RT_SCALARS) {
    const surface_point<T> p{{0, 0, 0}, {T(1e-4), T(1e-4), T(1e-4)}};
    const vec3<T> n(0, 1, 0);
    const vec3<T> up(T(0.5), T(0.5), 0), down(T(0.5), T(-0.5), 0);
    CHECK_MESSAGE(offset_ray_origin(p, n, up).y > T(0), "a ray leaving upwards (dot(w, n) > 0) starts above the surface");
    CHECK_MESSAGE(offset_ray_origin(p, n, down).y < T(0),
                  "a ray going through the surface (dot(w, n) < 0, a refracted ray) starts below it");
    // The normal's sign does not matter: the side is the ray's.
    CHECK_MESSAGE(offset_ray_origin(p, -n, up).y > T(0), "with the normal flipped, the upward ray still starts above");
    CHECK_MESSAGE(offset_ray_origin(p, -n, down).y < T(0), "with the normal flipped, the downward ray still starts below");
}

TEST_CASE_TEMPLATE("spawn: the push covers the whole error bound and only a float step more", T, RT_SCALARS) {
    for (const auto& c : rt::test::stiff_spawn_cases<T>(9021, 40)) {
        const vec3<T> n = c.outward;
        const vec3<T> w = mirror(c.incoming, n);
        const vec3<T> o = offset_ray_origin(c.surface, n, w);
        const T reach = rt::test::reach_along(c.surface, n);
        const T along = dot(o - c.surface.point, n);
        CAPTURE(c.family);
        CAPTURE(describe(c.surface.point));
        CAPTURE(reach);
        CAPTURE(along);
        CHECK_MESSAGE(along >= reach * (T(1) - T(8) * std::numeric_limits<T>::epsilon()),
                      "the origin moves at least dot(|n|, error) along n");
        CHECK_MESSAGE(along <= T(2) * (reach + rt::test::float_steps_along(c.surface.point, n)),
                      "the origin moves at most dot(|n|, error) plus one float step per component");
    }
}

TEST_CASE_TEMPLATE("spawn: no secondary ray starts on the wrong side of its surface on the stiff cases", T, RT_SCALARS) {
    // Four rays leave each point: reflected and refracted, arriving from
    // outside and from inside. Counted per family, so a failure names it.
    std::map<std::string, int> wrong, seen;
    for (const auto& c : rt::test::stiff_spawn_cases<T>(9022, 60)) {
        const vec3<T> out = c.outward;
        struct leaving {
            vec3<T> facing, w;
            int side;
        };
        const leaving rays[] = {
            {out, mirror(c.incoming, out), +1},    // reflected off the outside: stays out
            {out, c.incoming, -1},                 // refracted in: starts inside
            {-out, mirror(-c.incoming, -out), -1}, // reflected inside (arriving from inside): stays in
            {-out, -c.incoming, +1},               // refracted out: starts outside
        };
        for (const leaving& l : rays) {
            const vec3<T> o = offset_ray_origin(c.surface, l.facing, l.w);
            ++seen[c.family];
            if (c.side(o) != l.side) ++wrong[c.family];
        }
    }
    for (const auto& [family, n] : seen) {
        CAPTURE(family);
        CHECK_MESSAGE(wrong[family] == 0, wrong[family] << " of " << n
                                                        << " spawned rays start on the wrong side of the exact surface (a "
                                                           "reflected ray that re-hits its mirror, a refracted one that "
                                                           "never gets in): push by the error bound, along the normal, "
                                                           "to the side the ray leaves by");
    }
}

TEST_CASE_TEMPLATE("spawn: a thin shell is not skipped", T, RT_SCALARS) {
    // A second surface parallel to the first, 2 (dot(|n|, error) + one float
    // step per component) away: the spawned ray must start before it, on
    // either side (a glass pane's far face, a coating above a mirror).
    int skipped = 0, total = 0;
    for (const auto& c : rt::test::stiff_spawn_cases<T>(9023, 40)) {
        const vec3<T> n = c.outward;
        const T reach = rt::test::reach_along(c.surface, n);
        const rt::test::quad shell = 2 * (rt::test::quad(reach) + rt::test::quad(rt::test::float_steps_along(c.surface.point, n)));
        for (const vec3<T>& w : {mirror(c.incoming, n), c.incoming}) {
            const vec3<T> o = offset_ray_origin(c.surface, n, w);
            const vec3<T> moved = o - c.surface.point;  // exact in T for a push of a few ulps
            const rt::test::quad along = rt::test::quad_dot(moved, n);
            ++total;
            if (!(along < shell && along > -shell)) ++skipped;
        }
    }
    CHECK_MESSAGE(skipped == 0, skipped << " of " << total
                                        << " spawned rays start beyond a surface 2 (dot(|n|, error) + float steps) away: "
                                           "an offset larger than the bound skips thin shells");
}

TEST_CASE_TEMPLATE("spawn: a ray entering and leaving a glass sphere bends back to its first angle", T, RT_SCALARS) {
    // Through a ball, the exit angle equals the entry angle (the chord meets
    // both ends of the sphere at the same angle). Uses chapter 02's sphere
    // test, your refract and your spawn.
    const sphere<T> ball{{0, 0, -5}, 1, 0};
    const T eta = T(1) / T(1.5);
    for (T y : {T(0.1), T(0.4), T(0.7), T(0.95)}) {
        const ray<T> r{{0, y, 0}, {0, 0, -1}};
        const auto in = ch02::intersect_sphere(ball, r, rt::test::everything_ahead<T>());
        REQUIRE(in.has_value());
        const surface_point<T> entry = ch09::on_sphere(ball, in->point);
        const vec3<T> n_in = in->normal;
        const auto t_in = ch09::refract(r.direction, n_in, eta);
        REQUIRE_MESSAGE(t_in.has_value(), "a ray from air into glass is always transmitted");
        const ray<T> inside = ch09::spawn_ray(entry, n_in, *t_in);
        CHECK_MESSAGE(rt::test::sphere_side(ball, inside.origin) < 0, "the refracted ray must start inside the ball");
        const auto out = ch02::intersect_sphere(ball, inside, rt::test::everything_ahead<T>());
        REQUIRE_MESSAGE(out.has_value(), "from inside, the ray meets the far side of the ball");
        CHECK_MESSAGE(length(out->point - in->point) > T(0.1), "the ray crosses the ball, not its own entry point");
        const vec3<T> n_out = -out->normal;  // facing the ray, which comes from inside
        const T cos_entry = -dot(r.direction, n_in) / length(r.direction);
        const T cos_inside = -dot(*t_in, n_out);
        const auto t_out = ch09::refract(*t_in, n_out, T(1.5));
        REQUIRE_MESSAGE(t_out.has_value(), "the ray leaves the ball at the angle it entered it, so it is not trapped");
        const T cos_exit = -dot(*t_out, n_out);
        CAPTURE(y);
        CHECK_MESSAGE(std::fabs(cos_inside - -dot(*t_in, n_in)) <= T(1e-3), "inside, the chord meets both ends at one angle");
        CHECK_MESSAGE(std::fabs(cos_exit - cos_entry) <= (sizeof(T) == 4 ? T(1e-3) : T(1e-9)),
                      "the ray leaves at the angle it came in: cos " << cos_entry << " in, " << cos_exit << " out");
    }
}
