// Public tests for chapter 10, exercises 1 to 3: transform_ray,
// transform_normal, instance_box (transform.hpp).
#include "ch10_scenes.hpp"

#include "test_support.hpp"

#include <random>
#include <stdexcept>
#include <string>

using namespace rt;
using namespace rt::ch10;
using namespace rt::ch10::test;
using rt::test::describe;

TEST_CASE_TEMPLATE("transform: a translation moves the origin, never the direction", T, RT_SCALARS) {
    const placement<T> p = make_placement<T>(translate({1, 2, 3}));
    const ray<T> r{{T(0.5), T(-1), T(4)}, {T(0), T(0.25), T(-2)}};
    const ray<T> moved = transform_ray(p.to_world, r);
    CHECK_MESSAGE(moved.origin == vec3<T>(T(1.5), T(1), T(7)),
                  "the origin is a point: it moves by the translation b (A is the identity here), got "
                      << describe(moved.origin));
    CHECK_MESSAGE(moved.direction == r.direction,
                  "the direction is a difference of two points, (o + d) - o: the translation cancels, so d' = A d "
                  "with no b. Got "
                      << describe(moved.direction) << " for " << describe(r.direction));
}

TEST_CASE_TEMPLATE("transform: the direction is not normalised, so t names the same point in both spaces", T, RT_SCALARS) {
    // Scaling by 2 doubles the direction: the point at t in one space is the point at t in the other.
    const placement<T> p = make_placement<T>(compose(translate({1, 0, 0}), scale({2, 2, 2})));
    const ray<T> r{{T(0), T(0), T(5)}, {T(0), T(0), T(-1)}};
    const ray<T> world = transform_ray(p.to_world, r);
    CHECK_MESSAGE(world.direction == vec3<T>(T(0), T(0), T(-2)),
                  "under a scale of 2 the direction (0, 0, -1) becomes (0, 0, -2): do not normalise it, or t no "
                  "longer means the same point (chapter 01's convention: the direction has any length). Got "
                      << describe(world.direction));
    for (T t : {T(0.5), T(1), T(3.25)}) {
        const vec3<T> object_point = r.at(t);
        const vec3<L> exact = exact_point(p.to_world, object_point);
        CHECK_MESSAGE(bound_ratio(world.at(t), exact, vec3<L>(1e-5)) <= 1,
                      "the world ray at t = " << t << " must be the object point at t, mapped: got "
                                              << describe(world.at(t)));
    }
}

TEST_CASE_TEMPLATE("transform: every component of the ray is within the stated bound", T, RT_SCALARS) {
    // transform.hpp: origin within gamma(4) (|A||o| + |b|), direction within gamma(3) |A||d|, per component.
    std::mt19937_64 rng(1001);
    L worst_origin = 0, worst_direction = 0;
    std::string first;
    for (int i = 0; i < 400; ++i) {
        const placement<T> p = make_placement<T>(random_affine(rng, 0.01, 100, 2, i % 2 ? 1e4 : 1));
        const ray<T> r{convert<T>(random_unit(rng) * 50.0), convert<T>(random_unit(rng) * 3.0)};
        const ray<T> got = transform_ray(p.to_object, r);
        const L o = bound_ratio(got.origin, exact_point(p.to_object, r.origin),
                                term_magnitudes(p.to_object, r.origin, true) * L(gamma<T>(4)));
        const L d = bound_ratio(got.direction, exact_direction(p.to_object, r.direction),
                                term_magnitudes(p.to_object, r.direction, false) * L(gamma<T>(3)));
        if ((o > 1 || d > 1) && first.empty())
            first = describe_ray(r) + " went to " + describe_ray(got) + " (" + std::to_string(double(o)) + " and " +
                    std::to_string(double(d)) + " times the bound)";
        worst_origin = std::fmax(worst_origin, o);
        worst_direction = std::fmax(worst_direction, d);
    }
    INFO("largest error / bound: origin " << double(worst_origin) << ", direction " << double(worst_direction));
    CHECK_MESSAGE(first.empty(), "o' = A o + b and d' = A d (no translation), each component a sum of products: "
                                     << first);
}

TEST_CASE_TEMPLATE("transform: normals under non-uniform scale and shear stay perpendicular to the surface", T, RT_SCALARS) {
    std::mt19937_64 rng(1002);
    std::string first;
    for (int i = 0; i < 300; ++i) {
        const affine3<double> m = random_affine(rng, 0.2, 5, 1, 10);
        const placement<T> p = make_placement<T>(m);
        // A surface through the origin with normal n has tangents t1, t2 (both perpendicular to n).
        const vec3d n = random_unit(rng);
        const vec3d t1 = normalize(cross(n, random_unit(rng)));
        const vec3d t2 = cross(n, t1);
        const vec3<T> got = transform_normal(p, convert<T>(n));
        const vec3d g(got);
        const double unit_error = std::fabs(length(g) - 1);
        const double across1 = std::fabs(dot(g, normalize(m.linear * t1)));
        const double across2 = std::fabs(dot(g, normalize(m.linear * t2)));
        const double allowed = 16 * std::numeric_limits<T>::epsilon();  // transform.hpp's bound
        if (!(unit_error <= 4 * std::numeric_limits<T>::epsilon() && across1 <= allowed && across2 <= allowed) &&
            first.empty())
            first = "normal " + describe(convert<T>(n)) + " became " + describe(got) + ": |n . A t| = " +
                    std::to_string(std::fmax(across1, across2)) + ", |n| - 1 = " + std::to_string(unit_error);
    }
    CHECK_MESSAGE(first.empty(),
                  "a tangent t goes to A t; the normal must stay perpendicular to every A t. That is (A^-1)^T n "
                  "(p.to_object.linear, transposed), normalised; A n is perpendicular only when A is a rotation "
                  "times one scale: "
                      << first);
}

TEST_CASE_TEMPLATE("transform: a sphere squashed into an ellipsoid has the ellipsoid's normal", T, RT_SCALARS) {
    // The unit sphere scaled by (a, b, c) is x^2/a^2 + y^2/b^2 + z^2/c^2 = 1, whose normal at a point is
    // its gradient, (x/a^2, y/b^2, z/c^2).
    const vec3d abc(4, 1, 0.25);
    const placement<T> p = make_placement<T>(scale(abc));
    std::mt19937_64 rng(1003);
    for (int i = 0; i < 20; ++i) {
        const vec3d n = random_unit(rng);  // the sphere's normal at the point n
        const vec3d world_point = abc * n;
        const vec3d want = normalize(world_point / (abc * abc));
        const vec3<T> got = transform_normal(p, convert<T>(n));
        CHECK_MESSAGE(rt::test::close(got, convert<T>(want)),
                      "the ellipsoid's normal at " << describe(world_point) << " is " << describe(want) << ", got "
                                                   << describe(got) << " (the sphere's normal was " << describe(n)
                                                   << ")");
    }
}

TEST_CASE_TEMPLATE("transform: an instance's box contains every point of its object after rounding", T, RT_SCALARS) {
    std::mt19937_64 rng(1004);
    std::uniform_real_distribution<double> u(0, 1);
    std::string first;
    for (int i = 0; i < 200 && first.empty(); ++i) {
        const placement<T> p = make_placement<T>(random_affine(rng, 0.05, 20, 1, i % 2 ? 1e5 : 3));
        ch08::aabb<T> box;
        box.grow(convert<T>(random_unit(rng) * 2.0));
        box.grow(convert<T>(random_unit(rng) * 2.0));
        const ch08::aabb<T> world = instance_box(p.to_world, box);
        // Points of the box: its corners, points on its faces and inside; each mapped exactly and as
        // a renderer computes it (your transform_ray's origin).
        for (int k = 0; k < 64; ++k) {
            vec3<T> q;
            for (int c = 0; c < 3; ++c) {
                const double s = k < 8 ? double((k >> c) & 1) : (k % 3 == c ? double(k & 1) : u(rng));
                q[c] = T(double(box.lo[c]) + s * (double(box.hi[c]) - double(box.lo[c])));
                q[c] = std::fmin(std::fmax(q[c], box.lo[c]), box.hi[c]);
            }
            const vec3<T> rounded = transform_ray(p.to_world, ray<T>{q, vec3<T>(0)}).origin;
            const vec3<L> exact = exact_point(p.to_world, q);
            bool inside = true;
            for (int c = 0; c < 3; ++c)
                inside = inside && world.lo[c] <= rounded[c] && rounded[c] <= world.hi[c] && L(world.lo[c]) <= exact[c] &&
                         exact[c] <= L(world.hi[c]);
            if (!inside && first.empty())
                first = "the point " + describe(q) + " of the box " + describe(box.lo) + " .. " + describe(box.hi) +
                        " goes to " + describe(rounded) + ", outside " + describe(world.lo) + " .. " + describe(world.hi);
        }
    }
    CHECK_MESSAGE(first.empty(),
                  "map all eight corners (a turn moves corners other than lo and hi outside their box), then widen "
                  "every face by the pad in transform.hpp (the corners, and the hit points, are rounded): "
                      << first);
}

TEST_CASE_TEMPLATE("transform: an instance's box is tight: no larger than the corners' box and its pad", T, RT_SCALARS) {
    std::mt19937_64 rng(1005);
    for (int i = 0; i < 50; ++i) {
        const placement<T> p = make_placement<T>(random_affine(rng, 0.5, 2, 0.5, 10));
        const ch08::aabb<T> box{vec3<T>(T(-1), T(-0.5), T(0)), vec3<T>(T(1), T(2), T(0.25))};
        const ch08::aabb<T> world = instance_box(p.to_world, box);
        ch08::aabb<double> exact;
        // The exact images of the eight corners (each coordinate lo or hi).
        for (T x : {box.lo.x, box.hi.x})
            for (T y : {box.lo.y, box.hi.y})
                for (T z : {box.lo.z, box.hi.z}) exact.grow(vec3d(exact_point(p.to_world, vec3<T>(x, y, z))));
        const double slack = 1e-3;  // far more than any pad here (the box is of size about 1 at about 10)
        CHECK_MESSAGE((world.lo.x >= exact.lo.x - slack && world.lo.y >= exact.lo.y - slack &&
                       world.lo.z >= exact.lo.z - slack && world.hi.x <= exact.hi.x + slack &&
                       world.hi.y <= exact.hi.y + slack && world.hi.z <= exact.hi.z + slack),
                      "the box around the eight mapped corners, widened by a few roundings, is "
                          << describe(exact.lo) << " .. " << describe(exact.hi) << "; got " << describe(world.lo)
                          << " .. " << describe(world.hi));
    }
}

TEST_CASE_TEMPLATE("transform: the box of an empty box is empty", T, RT_SCALARS) {
    const placement<T> p = make_placement<T>(rotate({1, 2, 3}, 30));
    CHECK_MESSAGE(instance_box(p.to_world, ch08::aabb<T>{}).empty(),
                  "an empty box (lo = +inf, hi = -inf) holds nothing: its corners are not points; return the empty box");
}

TEST_CASE_TEMPLATE("transform: a singular transform is refused with a clear message", T, RT_SCALARS) {
    // Given code (make_placement), not an exercise: a scale of 0 flattens space, and there is no way back.
    for (const affine3<double>& m : {scale({1, 0, 1}), frame({1, 0, 0}, {0, 1, 0}, {1, 1, 0})}) {
        std::string message;
        try {
            (void)make_placement<T>(m, "scene.json:12: instances[3]");
        } catch (const std::invalid_argument& e) {
            message = e.what();
        }
        CHECK_MESSAGE(message.find("scene.json:12: instances[3] is singular") == 0,
                      "make_placement must refuse a singular transform, naming where it came from; got \"" << message
                                                                                                         << "\"");
    }
    // Very unequal scales, yet invertible: there and back again with your transform_ray.
    const placement<T> p = make_placement<T>(compose(rotate({1, 1, 0}, 40), scale({1e-3, 1, 1e3})));
    const ray<T> r{{T(1), T(2), T(3)}, {T(0.5), T(-1), T(0.25)}};
    const ray<T> back = transform_ray(p.to_world, transform_ray(p.to_object, r));
    CHECK_MESSAGE((rt::test::close(back.origin, r.origin) && rt::test::close(back.direction, r.direction)),
                  "to_world undoes to_object: " << describe_ray(r) << " came back as " << describe_ray(back));
}
