// Hidden tests for chapter 10 (run by the autograder only).
//
// Families, each from a fixed seed of its own, in both precisions:
//   transform   transform_ray within its stated bound for turns, shears,
//               scales from 1e-3 to 1e3 and translations up to 1e6; the
//               direction takes no translation and keeps its length's
//               meaning; normals perpendicular to mapped tangents under
//               non-uniform scale and shear; instance boxes that hold every
//               point of the box mapped exactly and as computed in T
//               (nearly axis-aligned transforms, where a box that is not
//               widened loses rounded points), and all eight corners
//   instancing  instance_hit's one call (its model, its ray, its range,
//               unchanged) and its record (t as the model gave it, point,
//               normal, object number); scenes built flat and from instances
//               (triangles under any affine map, spheres under similarities)
//               give the same object and t within the stated bound; the
//               sphereflake of level 3 as instances of instances; ties to
//               the lowest object number; pruning counted along a row;
//               any_hit stops at the first hit and agrees with closest_hit
// Failure messages name the idea that went wrong, never inputs or expected
// values: every check is a plain bool computed beforehand.
#include "../public/ch10_scenes.hpp"

#include "test_support.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace rt;
using namespace rt::ch10;
using namespace rt::ch10::test;

namespace {

template <class T>
bool same_bits(T a, T b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class T>
bool t_within(T got, T want, T conditioning) {
    return t_error_epsilons(got, want, conditioning) <= flat_t_bound_epsilons<T>;
}

template <class T>
std::vector<shape_model<T>> unit_sphere_model() {
    shape_model<T> m;
    m.spheres.push_back({vec3<T>(0), T(1)});
    return {m};
}

inline shape_model<double> mixed_model(bool spheres) {
    shape_model<double> m;
    if (spheres) {
        m.spheres.push_back({{0.2, 0, 0}, 1.0});
        m.spheres.push_back({{-1.2, 0.7, 0.3}, 0.4});
    }
    m.triangles.push_back({{-1, -1, 1.2}, {1, -1, 1.2}, {0, 1, 1.2}});
    m.triangles.push_back({{1.5, -1, -1}, {1.5, 1, -1}, {1.5, 0, 1}});
    m.triangles.push_back({{-1, -1.5, -1}, {1, -1.5, 0}, {0, -1.5, 1}});
    return m;
}

// Instances of one model, placed by `place`, and the same scene built flat; compares closest_hit with
// the flat answer on rays aimed at the objects. Returns false at the first difference.
template <class T, class Place>
bool flat_equals_instances(std::mt19937_64& rng, const shape_model<double>& model, int instances, Place&& place,
                           int rays, int& compared) {
    std::vector<shape_model<T>> models{convert_model<T>(model)};
    flat_scene<T> flat;
    std::vector<instance<T>> list;
    for (int k = 0; k < instances; ++k) {
        const affine3<double> m = place(rng);
        list.push_back({make_placement<T>(m), 0, k * model.count()});
        flat.parts.emplace_back();
        place_flat(model, m, flat.parts.back());
        flat.first.push_back(k * model.count());
    }
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    bool all = true;
    for (int i = 0; i < rays && all; ++i) {
        const auto& part = flat.parts[size_t(i) % flat.parts.size()];
        const vec3<T> at = part.triangles[size_t(i) % part.triangles.size()].a * T(0.4) +
                           part.triangles[size_t(i) % part.triangles.size()].b * T(0.3) +
                           part.triangles[size_t(i) % part.triangles.size()].c * T(0.3);
        const vec3<T> from = at + convert<T>(random_unit(rng) * 30.0);
        const ray<T> r{from, at - from};
        const interval<T> range{T(0), infinity<T>};
        const auto want = flat.closest(r, range);
        if (!want || std::fabs(dot(normalize(r.direction), want->normal)) < T(0.2)) continue;
        ++compared;
        const auto got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r, range);
        all = got && got->object == want->object && t_within(got->t, want->t, flat.conditioning(want->object, r, want->t));
    }
    return all;
}

}  // namespace

// ---- transform ------------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: transform: rays within the stated bound, from tiny scales to huge translations", T, RT_SCALARS) {
    std::mt19937_64 rng(91001);
    bool within = true;
    for (int i = 0; i < 600 && within; ++i) {
        const double reach = i % 3 == 0 ? 1e6 : (i % 3 == 1 ? 1e2 : 1e-2);
        const placement<T> p = make_placement<T>(random_affine(rng, 1e-3, 1e3, 3, reach));
        const ray<T> r{convert<T>(random_unit(rng) * (i % 2 ? 1e4 : 0.5)), convert<T>(random_unit(rng) * 7.0)};
        for (const affine3<T>* m : {&p.to_world, &p.to_object}) {
            const ray<T> got = transform_ray(*m, r);
            within = within &&
                     bound_ratio(got.origin, exact_point(*m, r.origin), term_magnitudes(*m, r.origin, true) * L(gamma<T>(4))) <= 1 &&
                     bound_ratio(got.direction, exact_direction(*m, r.direction),
                                 term_magnitudes(*m, r.direction, false) * L(gamma<T>(3))) <= 1;
        }
    }
    CHECK_MESSAGE(within, "transform_ray: o' = A o + b and d' = A d, within the bound transform.hpp states");
}

TEST_CASE_TEMPLATE("hidden: transform: the direction takes no translation and is not normalised", T, RT_SCALARS) {
    const placement<T> p = make_placement<T>(compose(translate({1e3, -250, 7}), scale({3, 3, 3})));
    const ray<T> r{{T(1), T(2), T(3)}, {T(0.5), T(0), T(-0.25)}};
    const ray<T> got = transform_ray(p.to_world, r);
    const bool no_translation = got.direction == vec3<T>(T(1.5), T(0), T(-0.75));
    CHECK_MESSAGE(no_translation, "transform_ray: a direction is a difference of points: A d, no translation, "
                                  "and not normalised (t must mean the same point in both spaces)");
}

TEST_CASE_TEMPLATE("hidden: transform: normals stay perpendicular to the surface under scale and shear", T, RT_SCALARS) {
    std::mt19937_64 rng(91002);
    bool perpendicular = true, unit = true;
    for (int i = 0; i < 400; ++i) {
        const affine3<double> m = random_affine(rng, 0.2, 5, 1, 1e3);
        const placement<T> p = make_placement<T>(m);
        const vec3d n = random_unit(rng);
        const vec3d t1 = normalize(cross(n, random_unit(rng)));
        const vec3d t2 = cross(n, t1);
        const vec3d g(transform_normal(p, convert<T>(n)));
        const double eps = std::numeric_limits<T>::epsilon();
        perpendicular = perpendicular && std::fabs(dot(g, normalize(m.linear * t1))) <= 16 * eps &&
                        std::fabs(dot(g, normalize(m.linear * t2))) <= 16 * eps;
        unit = unit && std::fabs(length(g) - 1) <= 4 * eps;
    }
    CHECK_MESSAGE(perpendicular, "transform_normal: normals go by the inverse transpose, so they stay perpendicular "
                                 "to every mapped tangent under non-uniform scale and shear");
    CHECK_MESSAGE(unit, "transform_normal: the world normal is unit length");
}

TEST_CASE_TEMPLATE("hidden: transform: an instance's box holds every point of the box, exact and rounded", T, RT_SCALARS) {
    // Nearly axis-aligned maps: along a face the mapped points' coordinate barely changes, so rounded
    // points of the face land beyond the rounded corners by an ulp unless the box is widened.
    std::mt19937_64 rng(91003);
    std::uniform_real_distribution<double> u(0, 1);
    bool inside = true;
    for (int i = 0; i < 300 && inside; ++i) {
        affine3<double> m;
        if (i % 2 == 0) {
            m = compose(translate({u(rng) * 1e3 + 0.1, u(rng) * 3 - 1.7, -u(rng) * 1e2}),
                        scale({1.0 / 3 + u(rng), 0.7 + u(rng), 1.1 + u(rng)}));
            m.linear[1][0] = 1e-7 * (u(rng) - 0.5);  // a hair of shear
            m.linear[2][1] = 1e-7 * (u(rng) - 0.5);
        } else {
            m = random_affine(rng, 0.01, 100, 2, 1e5);
        }
        const placement<T> p = make_placement<T>(m);
        ch08::aabb<T> box;
        box.grow(convert<T>(random_unit(rng) * 3.0 + vec3d(0.3)));
        box.grow(convert<T>(random_unit(rng) * 3.0));
        const ch08::aabb<T> world = instance_box(p.to_world, box);
        for (int k = 0; k < 200 && inside; ++k) {
            vec3<T> q;
            for (int c = 0; c < 3; ++c) {
                const double s = k < 8 ? double((k >> c) & 1) : (k % 3 == c ? double(k & 1) : u(rng));
                q[c] = T(double(box.lo[c]) + s * (double(box.hi[c]) - double(box.lo[c])));
                q[c] = std::fmin(std::fmax(q[c], box.lo[c]), box.hi[c]);
            }
            const vec3<T> rounded = transform_ray(p.to_world, ray<T>{q, vec3<T>(0)}).origin;
            const vec3<L> exact = exact_point(p.to_world, q);
            for (int c = 0; c < 3; ++c)
                inside = inside && world.lo[c] <= rounded[c] && rounded[c] <= world.hi[c] && L(world.lo[c]) <= exact[c] &&
                         exact[c] <= L(world.hi[c]);
        }
    }
    CHECK_MESSAGE(inside, "instance_box: the box of all eight mapped corners, widened against rounding, holds every "
                          "point of the object as the renderer computes it");
}

TEST_CASE_TEMPLATE("hidden: transform: an instance's box is tight and an empty box stays empty", T, RT_SCALARS) {
    std::mt19937_64 rng(91004);
    bool tight = true;
    for (int i = 0; i < 100; ++i) {
        const placement<T> p = make_placement<T>(random_affine(rng, 0.5, 2, 0.5, 50));
        const ch08::aabb<T> box{convert<T>(vec3d(-1, -2, -0.5)), convert<T>(vec3d(0.5, 1, 1.5))};
        const ch08::aabb<T> world = instance_box(p.to_world, box);
        ch08::aabb<double> exact;
        for (int c = 0; c < 8; ++c) {
            const vec3<T> corner{c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z};
            exact.grow(vec3d(exact_point(p.to_world, corner)));
        }
        const double slack = 1e-2;
        for (int k = 0; k < 3; ++k)
            tight = tight && world.lo[k] >= exact.lo[k] - slack && world.hi[k] <= exact.hi[k] + slack;
    }
    CHECK_MESSAGE(tight, "instance_box: no larger than the mapped corners' box and its pad");
    const placement<T> p = make_placement<T>(rotate({0, 1, 1}, 70));
    CHECK_MESSAGE(instance_box(p.to_world, ch08::aabb<T>{}).empty(), "instance_box: an empty box stays empty");
}

// ---- instancing -----------------------------------------------------------

TEST_CASE_TEMPLATE("hidden: instancing: the model is asked once, about the object-space ray and the same range", T, RT_SCALARS) {
    std::mt19937_64 rng(92001);
    const std::vector<shape_model<T>> models = unit_sphere_model<T>();
    std::uniform_real_distribution<double> u(0, 1);
    bool as_expected = true;
    for (int i = 0; i < 60; ++i) {
        const instance<T> inst{make_placement<T>(random_affine(rng, 0.2, 5, 0.5, 20)), 0, 3};
        const vec3<T> centre = inst.place.to_world.translation;
        const vec3<T> from = centre + convert<T>(random_unit(rng) * 40.0);
        const ray<T> r{from, (centre - from) * T(0.5 + u(rng))};
        const interval<T> range{T(i % 3 == 0 ? -1 : u(rng)), i % 2 ? infinity<T> : T(10 + 100 * u(rng))};
        rt::test::served_objects<T> served = served_for(models, {inst}, r, 1);
        served.check_calls = true;
        served.expected = {{0, range}};
        bool ok = true;
        try {
            (void)instance_hit(inst, model_intersector<T>(served), r, range);
        } catch (const rt::test::broken_rule<T>&) {
            ok = false;
        }
        as_expected = as_expected && ok;
    }
    CHECK_MESSAGE(as_expected, "instance_hit: one call of the model, about transform_ray(to_object, r) and the very "
                               "range given (t is the same in both spaces)");
}

TEST_CASE_TEMPLATE("hidden: instancing: the record is brought back to the world", T, RT_SCALARS) {
    std::mt19937_64 rng(92002);
    const std::vector<shape_model<T>> models = unit_sphere_model<T>();
    bool same_t = true, point = true, normal = true, object = true;
    int hits = 0;
    for (int i = 0; i < 80; ++i) {
        const affine3<double> m = random_similarity(rng, 0.3, 4, 30);
        const instance<T> inst{make_placement<T>(m), 0, 11 + i};
        const vec3<T> centre = inst.place.to_world.translation;
        const vec3<T> from = centre + convert<T>(random_unit(rng) * 25.0);
        const vec3<T> aim = centre + convert<T>(random_unit(rng) * 0.3 * glm::length(m.linear[0]));
        const ray<T> r{from, aim - from};
        const interval<T> range{T(0), infinity<T>};
        const auto got = instance_hit(inst, model_intersector<T>(served_for(models, {inst}, r)), r, range);
        const auto model_answer = models[0].closest(transform_ray(inst.place.to_object, r), range);
        if (!model_answer || !got) {
            same_t = same_t && !model_answer && !got;
            continue;
        }
        ++hits;
        same_t = same_t && same_bits(got->t, model_answer->t);
        const vec3<L> exact = exact_point(inst.place.to_world, model_answer->point);
        point = point && bound_ratio(got->point, exact,
                                     term_magnitudes(inst.place.to_world, model_answer->point, true) * L(gamma<T>(4))) <= 1;
        const vec3<T> want_normal = normalize(got->point - centre);
        normal = normal && rt::test::close(got->normal, want_normal);
        object = object && got->object == 11 + i + model_answer->object;
    }
    CHECK(hits > 40);
    CHECK_MESSAGE(same_t, "instance_hit: t is the model's t, unchanged");
    CHECK_MESSAGE(point, "instance_hit: the point is the model's point mapped by to_world");
    CHECK_MESSAGE(normal, "instance_hit: the normal is the model's normal by transform_normal");
    CHECK_MESSAGE(object, "instance_hit: the object number is first_object plus the model's own");
}

TEST_CASE_TEMPLATE("hidden: instancing: triangles under any affine map: flat and instanced agree", T, RT_SCALARS) {
    std::mt19937_64 rng(92003);
    int compared = 0;
    const bool agree = flat_equals_instances<T>(
        rng, mixed_model(false), 40, [](std::mt19937_64& g) { return random_affine(g, 0.3, 3, 0.8, 20); }, 240, compared);
    CHECK(compared > 80);
    CHECK_MESSAGE(agree, "closest_hit over instances: the flat scene's object, at its t within the stated bound");
}

TEST_CASE_TEMPLATE("hidden: instancing: spheres and triangles under similarities: flat and instanced agree", T, RT_SCALARS) {
    std::mt19937_64 rng(92004);
    int compared = 0;
    const bool agree = flat_equals_instances<T>(
        rng, mixed_model(true), 30, [](std::mt19937_64& g) { return random_similarity(g, 0.2, 5, 1e3); }, 240,
        compared);
    CHECK(compared > 80);
    CHECK_MESSAGE(agree, "closest_hit over instances: the flat scene's object, at its t within the stated bound");
}

TEST_CASE_TEMPLATE("hidden: instancing: the sphereflake as instances of instances", T, RT_SCALARS) {
    const int level = 3;
    const std::vector<composite_model> parts = flake_models(level);
    std::vector<shape_model<T>> models{size_t(level)};
    std::vector<ch08::aabb<T>> boxes;
    for (int k = 0; k < level; ++k) {
        models[size_t(k)].spheres = flatten<T>(parts, k);
        boxes.push_back(models[size_t(k)].box());
    }
    std::vector<instance<T>> list;
    for (const part& p : parts[size_t(level)].parts) list.push_back({make_placement<T>(p.to_world), p.model, int(p.first_object)});
    const instance_tree<T> scene = build_instance_tree(list, boxes);
    shape_model<T> flat;
    flat.spheres = flatten<T>(parts, level);
    const flat_scene<T> flat_flake{{flat}, {0}};
    std::mt19937_64 rng(92005);
    int compared = 0;
    bool agree = true;
    for (int i = 0; i < 150 && agree; ++i) {
        const vec3<T> from = convert<T>(random_unit(rng) * (i % 2 ? 3.0 : 12.0));
        const vec3<T> at = flat.spheres[size_t(rng() % flat.spheres.size())].center;
        const ray<T> r{from, (at - from) * T(i % 3 + 1)};
        const interval<T> range{T(0), infinity<T>};
        const auto want = flat_flake.closest(r, range);
        if (!want || std::fabs(dot(normalize(r.direction), want->normal)) < T(0.2)) continue;
        ++compared;
        const auto got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r, range);
        agree = got && got->object == want->object &&
                t_within(got->t, want->t, flat_flake.conditioning(want->object, r, want->t));
    }
    CHECK(compared > 50);
    CHECK_MESSAGE(agree, "closest_hit over instances of instances: the flat flake's sphere, at its t");
}

TEST_CASE_TEMPLATE("hidden: instancing: equal t goes to the lowest object number", T, RT_SCALARS) {
    const std::vector<shape_model<T>> models = unit_sphere_model<T>();
    const affine3<double> m = compose(translate({2, -1, -9}), rotate({1, 0, 1}, 50));
    std::vector<instance<T>> list;
    for (int k = 0; k < 6; ++k) list.push_back({make_placement<T>(m), 0, 20 + 5 * k});
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    bool lowest = true;
    for (int i = 0; i < 5; ++i) {
        const ray<T> r{{T(2) + T(0.1) * T(i), T(-1), T(0)}, {T(0), T(0.01) * T(i), T(-1)}};
        const auto got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r,
                                     rt::test::everything_ahead<T>());
        lowest = lowest && got && got->object == 20;
    }
    CHECK_MESSAGE(lowest, "closest_hit over instances: of equal t, the lowest scene object number wins");
}

TEST_CASE_TEMPLATE("hidden: instancing: the nearest instance first, the rest pruned", T, RT_SCALARS) {
    const std::vector<shape_model<T>> models = unit_sphere_model<T>();
    std::vector<instance<T>> list;
    for (int k = 0; k < 64; ++k)
        list.push_back({make_placement<T>(compose(translate({0.1, 0, -2.5 * k}), scale(vec3d(0.5 + 0.01 * k)))), 0, k});
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    const ray<T> r{{T(0), T(0), T(8)}, {T(0.001), T(0), T(-2)}};
    bool pruned = true;
    std::optional<hit_record<T>> got;
    try {
        got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r, 6)), r,
                          rt::test::everything_ahead<T>());
    } catch (const rt::test::broken_rule<T>&) {
        pruned = false;
    }
    CHECK_MESSAGE(pruned, "closest_hit over instances: instances beyond the closest hit are skipped, not asked");
    CHECK_MESSAGE((!pruned || (got && got->object == 0)), "closest_hit over instances: the nearest instance is hit");
}

TEST_CASE_TEMPLATE("hidden: instancing: any_hit agrees with closest_hit and stops at the first hit", T, RT_SCALARS) {
    std::mt19937_64 rng(92006);
    std::vector<shape_model<T>> models{convert_model<T>(mixed_model(true))};
    std::vector<instance<T>> list;
    for (int k = 0; k < 30; ++k) list.push_back({make_placement<T>(random_similarity(rng, 0.3, 2, 15)), 0, 5 * k});
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    bool agree = true, stops = true;
    for (int i = 0; i < 200; ++i) {
        const vec3<T> from = convert<T>(random_unit(rng) * 30.0);
        const vec3<T> to = convert<T>(random_unit(rng) * 10.0);
        const ray<T> r{from, to - from};
        const interval<T> range{T(0), i % 2 ? infinity<T> : T(0.5)};
        const bool hit = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r, range).has_value();
        agree = agree && any_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r, range) == hit;
    }
    // Every instance on the ray: one call answers.
    std::vector<instance<T>> row;
    for (int k = 0; k < 20; ++k) row.push_back({make_placement<T>(translate({0, 0, -3.0 * k})), 0, 5 * k});
    const instance_tree<T> line = build_instance_tree(row, {models[0].box()});
    const ray<T> r{{T(0.2), T(0), T(10)}, {T(0), T(0), T(-1)}};
    try {
        stops = any_hit(line, model_intersector<T>(served_for(models, line.instances, r, 1)), r,
                        rt::test::everything_ahead<T>());
    } catch (const rt::test::broken_rule<T>&) {
        stops = false;
    }
    CHECK_MESSAGE(agree, "any_hit over instances: true exactly when closest_hit finds a hit");
    CHECK_MESSAGE(stops, "any_hit over instances: no model is asked after one answered with a hit");
}
