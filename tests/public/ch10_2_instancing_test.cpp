// Public tests for chapter 10, exercises 4 and 5: instance_hit, and the
// two-level closest_hit and any_hit (instancing.hpp).
//
// The models are answered by the tests (ch10_scenes.hpp): every call your
// code makes to model_hit is checked against the rules, from the record of
// the calls the test answered: the model must be the instance's, the ray
// your own transform_ray(inst.place.to_object, r), bit for bit.
#include "ch10_scenes.hpp"

#include "test_support.hpp"

#include <random>
#include <string>
#include <vector>

using namespace rt;
using namespace rt::ch10;
using namespace rt::ch10::test;
using rt::test::describe;
using rt::test::describe_hit;

namespace {

template <class T>
std::string object_of(const std::optional<hit_record<T>>& hit) {
    return hit ? "object " + std::to_string(hit->object) + ", " + describe_hit(hit) : describe_hit(hit);
}

// One sphere of radius 1 at the origin: the model of the first tests.
template <class T>
std::vector<shape_model<T>> one_sphere() {
    shape_model<T> m;
    m.spheres.push_back({vec3<T>(0), T(1)});
    return {m};
}

// t within the stated bound of the flat t (ch10_scenes.hpp, flat_t_bound_epsilons).
template <class T>
bool t_close(T got, T want, T conditioning = T(1)) {
    return t_error_epsilons(got, want, conditioning) <= flat_t_bound_epsilons<T>;
}

// Instances of `models` placed by random similarities along a row, and the same scene built flat.
template <class T>
struct two_ways {
    std::vector<shape_model<T>> models;
    instance_tree<T> scene;
    flat_scene<T> flat;
};

template <class T>
two_ways<T> random_scene(std::mt19937_64& rng, const std::vector<shape_model<double>>& models, int instances,
                         double reach) {
    two_ways<T> s;
    std::vector<ch08::aabb<T>> boxes;
    for (const auto& m : models) {
        s.models.push_back(convert_model<T>(m));
        boxes.push_back(s.models.back().box());
    }
    std::vector<instance<T>> list;
    int next = 0;
    for (int k = 0; k < instances; ++k) {
        const int model = k % int(models.size());
        const affine3<double> m = random_similarity(rng, 0.3, 3, reach);
        list.push_back({make_placement<T>(m), model, next});
        s.flat.parts.emplace_back();
        place_flat(models[size_t(model)], m, s.flat.parts.back());
        s.flat.first.push_back(next);
        next += models[size_t(model)].count();
    }
    s.scene = build_instance_tree(list, boxes);
    return s;
}

// A model of two spheres and two triangles, in its own space.
inline shape_model<double> small_model() {
    shape_model<double> m;
    m.spheres.push_back({{0, 0, 0}, 1.0});
    m.spheres.push_back({{1.5, 0.5, 0}, 0.5});
    m.triangles.push_back({{-1, -1, 1.5}, {1, -1, 1.5}, {0, 1, 1.5}});
    m.triangles.push_back({{-2, -1, -1}, {-2, 1, -1}, {-2, 0, 1}});
    return m;
}

}  // namespace

TEST_CASE_TEMPLATE("instancing: instance_hit takes the ray in, asks the model once, and brings the hit back", T, RT_SCALARS) {
    // The unit sphere placed at (3, 0, 0) with radius 2: in the world, the sphere of centre (3, 0, 0), radius 2.
    const std::vector<shape_model<T>> models = one_sphere<T>();
    const instance<T> inst{make_placement<T>(compose(translate({3, 0, 0}), scale({2, 2, 2}))), 0, 7};
    const ray<T> r{{T(3), T(0.5), T(10)}, {T(0), T(0), T(-1)}};
    const interval<T> range{T(0), infinity<T>};
    rt::test::served_objects<T> served = served_for(models, {inst}, r);
    served.check_calls = true;
    served.expected = {{0, range}};
    const auto got = rt::test::call_with_rules<T>([&] { return instance_hit(inst, model_intersector<T>(served), r, range); });
    REQUIRE_MESSAGE(!got.broken, (got.broken ? rt::test::describe_fault(*got.broken, true) : std::string()));
    const auto want = ch02::intersect_sphere(sphere<T>{{T(3), T(0), T(0)}, T(2)}, r, range);
    REQUIRE_MESSAGE(got.answer.has_value(), "the ray crosses the placed sphere; got " << describe_hit(got.answer));
    CHECK_MESSAGE(t_close(got.answer->t, want->t),
                  "t is the same in both spaces (the direction is not normalised): the world sphere's t is "
                      << want->t << ", got " << got.answer->t);
    CHECK_MESSAGE(rt::test::close(got.answer->point, want->point),
                  "the point comes back by to_world: want " << describe(want->point) << ", got "
                                                            << describe(got.answer->point));
    CHECK_MESSAGE(rt::test::close(got.answer->normal, want->normal),
                  "the normal comes back by transform_normal: want " << describe(want->normal) << ", got "
                                                                     << describe(got.answer->normal));
    CHECK_MESSAGE(got.answer->object == 7, "the scene's number of the model's object 0 is inst.first_object (7); got "
                                               << got.answer->object);
}

TEST_CASE_TEMPLATE("instancing: the range is carried into the model's space unchanged", T, RT_SCALARS) {
    // A scale of 4 along the ray: a range that was rescaled or reset would show in the call.
    const std::vector<shape_model<T>> models = one_sphere<T>();
    const instance<T> inst{make_placement<T>(compose(translate({0, 0, -20}), scale({1, 1, 4}))), 0, 0};
    const ray<T> r{{T(0), T(0.25), T(0)}, {T(0), T(0), T(-1)}};
    for (const interval<T> range : {interval<T>{T(1), infinity<T>}, interval<T>{T(2.5), T(15.75)}, interval<T>{T(16.5), T(30)},
                                     interval<T>{T(-3), T(30)}}) {
        rt::test::served_objects<T> served = served_for(models, {inst}, r);
        served.check_calls = true;
        served.expected = {{0, range}};
        const auto got = rt::test::call_with_rules<T>([&] { return instance_hit(inst, model_intersector<T>(served), r, range); });
        CHECK_MESSAGE(!got.broken, "t means the same in both spaces, so the model is asked about the very range given ("
                                       << range.min << ", " << range.max << "): "
                                       << (got.broken ? rt::test::describe_fault(*got.broken, true) : std::string()));
        const bool hit_expected = range.max > T(16);  // the stretched sphere spans t = 16 to 24
        CHECK_MESSAGE(got.answer.has_value() == hit_expected,
                      "the placed sphere spans t = 16 to 24 along this ray (scaled by 4 along it); range (" << range.min << ", " << range.max
                                                                                     << ") got " << describe_hit(got.answer));
    }
}

TEST_CASE_TEMPLATE("instancing: a miss of the model is a miss of the instance", T, RT_SCALARS) {
    const std::vector<shape_model<T>> models = one_sphere<T>();
    const instance<T> inst{make_placement<T>(translate({0, 5, 0})), 0, 0};
    const ray<T> r{{T(0), T(0), T(5)}, {T(0), T(0), T(-1)}};
    const auto got = instance_hit(inst, model_intersector<T>(served_for(models, {inst}, r)), r,
                                  rt::test::everything_ahead<T>());
    CHECK_MESSAGE(!got, "the sphere sits at y = 5, the ray runs along y = 0: got " << describe_hit(got));
}

TEST_CASE_TEMPLATE("instancing: a scene built flat and from instances give the same objects and t", T, RT_SCALARS) {
    std::mt19937_64 rng(2001);
    const two_ways<T> s = random_scene<T>(rng, {small_model()}, 24, 12);
    int compared = 0;
    T worst = 0;
    std::string first;
    for (int i = 0; i < 150; ++i) {
        // Aim at a random object's centre region, from outside the scene.
        const vec3<T> from = convert<T>(random_unit(rng) * 40.0);
        const auto& part = s.flat.parts[size_t(i) % s.flat.parts.size()];
        const vec3<T> at = part.spheres[0].center;
        const ray<T> r{from, at - from};
        const interval<T> range{T(0), infinity<T>};
        const auto want = s.flat.closest(r, range);
        const auto got = closest_hit(s.scene, model_intersector<T>(served_for(s.models, s.scene.instances, r)), r, range);
        if (!want) continue;
        const vec3<T> unit = normalize(r.direction);
        if (std::fabs(dot(unit, want->normal)) < T(0.2)) continue;  // grazing: the bound is for good angles
        ++compared;
        const T conditioning = s.flat.conditioning(want->object, r, want->t);
        if (got) worst = std::fmax(worst, t_error_epsilons(got->t, want->t, conditioning));
        if ((!got || got->object != want->object || !t_close(got->t, want->t, conditioning)) && first.empty())
            first = describe_ray(r) + ": flat " + object_of(want) + "; from instances " + object_of(got);
    }
    INFO("largest |t - t_flat| / (epsilon t conditioning): " << worst);
    CHECK(compared > 50);
    CHECK_MESSAGE(first.empty(), "the instances' closest hit must be the flat scene's object, at its t within "
                                     << flat_t_bound_epsilons<T> << " epsilon of t: " << first);
}

TEST_CASE_TEMPLATE("instancing: equal t: the lowest scene object number wins", T, RT_SCALARS) {
    // Two instances in the same place: every hit of one is a hit of the other at the same t.
    std::vector<shape_model<T>> models = one_sphere<T>();
    const affine3<double> m = compose(translate({0, 0, -5}), rotate({0, 1, 0}, 30));
    std::vector<instance<T>> list{{make_placement<T>(m), 0, 3}, {make_placement<T>(m), 0, 4}};
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    const ray<T> r{{T(0.1), T(0.2), T(0)}, {T(0), T(0), T(-1)}};
    const auto got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r,
                                 rt::test::everything_ahead<T>());
    REQUIRE(got.has_value());
    CHECK_MESSAGE(got->object == 3, "two instances hit at the same t: the lower scene number (3) wins, as in "
                                    "chapter 03's loop; got "
                                        << got->object);
}

TEST_CASE_TEMPLATE("instancing: nearest instance first: a row of instances asks almost only the nearest", T, RT_SCALARS) {
    std::vector<shape_model<T>> models = one_sphere<T>();
    std::vector<instance<T>> list;
    for (int k = 0; k < 32; ++k)
        list.push_back({make_placement<T>(compose(translate({0, 0, -3.0 * k}), scale(vec3d(0.5)))), 0, k});
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    const ray<T> r{{T(0), T(0), T(10)}, {T(0), T(0), T(-1)}};
    const auto got = rt::test::call_with_rules<T>([&] {
        return closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r, 3)), r,
                           rt::test::everything_ahead<T>());
    });
    CHECK_MESSAGE(!got.broken, "the nearest instance is hit first; every other box then lies beyond that hit and "
                               "is skipped (chapter 08's closest_hit does this, if instance_hit is its leaf): "
                                   << (got.broken ? rt::test::describe_fault(*got.broken, true) : std::string()));
    if (!got.broken) {
        REQUIRE(got.answer.has_value());
        CHECK_MESSAGE(got.answer->object == 0, "the nearest instance is object 0; got " << got.answer->object);
    }
}

TEST_CASE_TEMPLATE("instancing: any_hit stops at the first instance hit", T, RT_SCALARS) {
    std::vector<shape_model<T>> models = one_sphere<T>();
    std::vector<instance<T>> list;
    for (int k = 0; k < 16; ++k) list.push_back({make_placement<T>(translate({0, 0, -3.0 * k})), 0, k});
    const instance_tree<T> scene = build_instance_tree(list, {models[0].box()});
    const ray<T> r{{T(0), T(0), T(10)}, {T(0), T(0), T(-1)}};
    // Every instance is on the ray: the first call already hits, so one call is all a shadow ray needs.
    const auto got = rt::test::call_with_rules<T>([&] {
        return any_hit(scene, model_intersector<T>(served_for(models, scene.instances, r, 1)), r,
                       rt::test::everything_ahead<T>());
    });
    CHECK_MESSAGE(!got.broken, "after one model answered with a hit, nothing more may be asked: "
                                   << (got.broken ? rt::test::describe_fault(*got.broken, true) : std::string()));
    CHECK_MESSAGE((got.broken || got.answer), "every instance lies on the ray: any_hit is true");
    const ray<T> away{{T(0), T(0), T(10)}, {T(0), T(0), T(1)}};
    CHECK_MESSAGE(!any_hit(scene, model_intersector<T>(served_for(models, scene.instances, away)), away,
                           rt::test::everything_ahead<T>()),
                  "a ray pointing away from every instance hits nothing");
}

TEST_CASE_TEMPLATE("instancing: an empty scene of instances is a miss and asks no model", T, RT_SCALARS) {
    std::vector<shape_model<T>> models = one_sphere<T>();
    const instance_tree<T> scene = build_instance_tree<T>({}, {models[0].box()});
    const ray<T> r{{T(0), T(0), T(10)}, {T(0), T(0), T(-1)}};
    const auto got = rt::test::call_with_rules<T>([&] {
        return closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r, 0)), r,
                           rt::test::everything_ahead<T>());
    });
    CHECK_MESSAGE((!got.broken && !got.answer), "no instances: nothing is hit and no model is asked");
}

TEST_CASE_TEMPLATE("instancing: the sphereflake as instances of instances is the flat flake", T, RT_SCALARS) {
    // Level 3: the top is ten instances (the root sphere, nine flakes of level 2). The models below the
    // top are answered by the test from their flat lists, in their own spaces; your closest_hit places them.
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
    REQUIRE(flat.spheres.size() == size_t(flake_sphere_count(level)));
    const flat_scene<T> flat_flake{{flat}, {0}};

    std::mt19937_64 rng(2002);
    int compared = 0;
    T worst = 0;
    std::string first;
    for (int i = 0; i < 120; ++i) {
        const vec3<T> from = convert<T>(random_unit(rng) * 4.0);
        const vec3<T> at = flat.spheres[size_t(rng() % flat.spheres.size())].center;
        const ray<T> r{from, at - from};
        const interval<T> range{T(0), infinity<T>};
        const auto want = flat.closest(r, range);
        const auto got = closest_hit(scene, model_intersector<T>(served_for(models, scene.instances, r)), r, range);
        if (!want || std::fabs(dot(normalize(r.direction), want->normal)) < T(0.2)) continue;
        ++compared;
        const T conditioning = flat_flake.conditioning(want->object, r, want->t);
        if (got) worst = std::fmax(worst, t_error_epsilons(got->t, want->t, conditioning));
        if ((!got || got->object != want->object || !t_close(got->t, want->t, conditioning)) && first.empty())
            first = describe_ray(r) + ": flat " + object_of(want) + "; from instances " + object_of(got);
    }
    INFO("largest |t - t_flat| / (epsilon t conditioning): " << worst);
    CHECK(compared > 40);
    CHECK_MESSAGE(first.empty(), "each of the flake's nine children is a scaled copy of the whole: the scene of "
                                 "instances must find the flat flake's sphere, at its t: "
                                     << first);
}
