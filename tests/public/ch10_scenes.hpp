// ch10_scenes.hpp — what chapter 10's tests share: transforms with exact
// references, models the tests answer themselves, scenes built both flat and
// from instances.
//
// Exact references: a transform applied in long double to inputs given in T.
// A float product is exact in long double and a sum of four such terms is
// within 2^-63 of exact; for double the reference is 11 bits finer than the
// bounds it checks (gamma(4) is about 4.4e-16). The models are answered by
// the tests (served callbacks, tests/support/rpc/served.hpp): under the
// grader the grader's own process answers every call your code makes to
// model_hit and keeps the record of those calls.
#pragma once

#include "10-transforms/instancing.hpp"
#include "10-transforms/sphereflake.hpp"
#include "10-transforms/transform.hpp"
#include "02-sphere/sphere.hpp"
#include "03-scene-loop/scene_loop.hpp"
#include "05-triangle/triangle.hpp"

#include "common/hit_record.hpp"
#include "rpc/served.hpp"
#include "test_support.hpp"

#include <cmath>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace rt::ch10::test {

using L = long double;

// m applied exactly (to rounding far below the bounds tested) to a point or a direction.
template <class T>
vec3<L> exact_point(const affine3<T>& m, const vec3<T>& p) {
    return glm::mat<3, 3, L>(m.linear) * vec3<L>(p) + vec3<L>(m.translation);
}
template <class T>
vec3<L> exact_direction(const affine3<T>& m, const vec3<T>& d) {
    return glm::mat<3, 3, L>(m.linear) * vec3<L>(d);
}

// (|A| |x| + |b|) in long double: the scale of transform_ray's bound. Without b for a direction.
template <class T>
vec3<L> term_magnitudes(const affine3<T>& m, const vec3<T>& x, bool with_translation) {
    vec3<L> s = glm::abs(glm::mat<3, 3, L>(m.linear)[0]) * std::fabs(L(x.x)) +
                glm::abs(glm::mat<3, 3, L>(m.linear)[1]) * std::fabs(L(x.y)) +
                glm::abs(glm::mat<3, 3, L>(m.linear)[2]) * std::fabs(L(x.z));
    if (with_translation) s += glm::abs(vec3<L>(m.translation));
    return s;
}

// The largest ratio |computed - exact| / bound over the components (<= 1 is within the bound; NaN and
// infinity give infinity).
template <class T>
L bound_ratio(const vec3<T>& computed, const vec3<L>& exact, const vec3<L>& bound) {
    L worst = 0;
    for (int k = 0; k < 3; ++k) {
        const L error = std::fabs(L(computed[k]) - exact[k]);
        if (!std::isfinite(L(computed[k]))) return infinity<L>;
        const L ratio = bound[k] > 0 ? error / bound[k] : (error > 0 ? infinity<L> : L(0));
        worst = std::fmax(worst, ratio);
    }
    return worst;
}

inline vec3d random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    vec3d v;
    do v = vec3d(n(rng), n(rng), n(rng));
    while (!(length(v) > 1e-3));
    return normalize(v);
}

// A random affine transform: a turn, a scale per axis in [s_lo, s_hi] (non-uniform), a shear of up
// to `shear` and a translation of up to `reach` in each coordinate.
inline affine3<double> random_affine(std::mt19937_64& rng, double s_lo, double s_hi, double shear, double reach) {
    std::uniform_real_distribution<double> s(s_lo, s_hi), h(-shear, shear), b(-reach, reach), angle(0, 360);
    affine3<double> sheared;
    sheared.linear[1][0] = h(rng);  // x += h y
    sheared.linear[2][1] = h(rng);  // y += h z
    sheared.linear[2][0] = h(rng);  // x += h z
    affine3<double> m = compose(rotate(random_unit(rng), angle(rng)), compose(sheared, scale({s(rng), s(rng), s(rng)})));
    return compose(translate({b(rng), b(rng), b(rng)}), m);
}

// A similarity (a turn, one scale, a translation): spheres stay spheres.
inline affine3<double> random_similarity(std::mt19937_64& rng, double s_lo, double s_hi, double reach) {
    std::uniform_real_distribution<double> s(s_lo, s_hi), b(-reach, reach), angle(0, 360);
    return compose(translate({b(rng), b(rng), b(rng)}), compose(rotate(random_unit(rng), angle(rng)), scale(vec3d(s(rng)))));
}

// ---- models the tests answer ----------------------------------------------

// A model: spheres, then triangles, numbered 0, 1, 2, ... in its own space.
template <class T>
struct shape_model {
    std::vector<sphere<T>> spheres;
    std::vector<triangle<T>> triangles;

    int count() const { return int(spheres.size() + triangles.size()); }

    // Object i's own test (chapter 02's sphere, chapter 05's triangle), object left for the loop to set.
    std::optional<hit_record<T>> test(int i, const ray<T>& r, const interval<T>& range) const {
        if (size_t(i) < spheres.size()) return ch02::intersect_sphere(spheres[size_t(i)], r, range);
        return ch05::intersect_triangle(triangles[size_t(i) - spheres.size()], r, range);
    }

    // Brute force: chapter 03's closest_hit over the model's objects, called through its header (in
    // your build it is your own chapter 03; the autograder uses the reference one), as chapter 08's
    // tests do: the smallest t in the open range, the lowest number on equal t.
    std::optional<hit_record<T>> closest(const ray<T>& r, const interval<T>& range) const {
        rt::test::served_objects<T> objects;
        objects.count = count();
        objects.test = [this](int i, const ray<T>& ray_, const interval<T>& range_) { return test(i, ray_, range_); };
        return ch03::closest_hit<T>(count(), objects, r, range);
    }

    ch08::aabb<T> box() const {
        ch08::aabb<T> b;
        for (const auto& s : spheres) b.grow(ch08::bounds(s));
        for (const auto& t : triangles) b.grow(ch08::bounds(t));
        return b;
    }
};

// The models of a test, answered by brute force, as a served callback: under the grader the
// grader's process answers, and keeps the record of the calls.
template <class T>
rt::test::served_objects<T> served_models(const std::vector<shape_model<T>>& models, long budget = -1) {
    rt::test::served_objects<T> s;
    s.count = int(models.size());
    s.test = [&models](int m, const ray<T>& r, const interval<T>& range) { return models[size_t(m)].closest(r, range); };
    s.budget = budget;
    return s;
}

// The calls a scene's instances may make for world ray r: each instance's model, asked about
// transform_ray(to_object, r) (your transform_ray: the rule is that instance_hit uses it, bit for bit).
template <class T>
std::vector<std::pair<int, ray<T>>> object_rays(const std::vector<instance<T>>& instances, const ray<T>& r) {
    std::vector<std::pair<int, ray<T>>> out;
    for (const instance<T>& inst : instances) out.emplace_back(inst.model, transform_ray(inst.place.to_object, r));
    return out;
}

// The served models for one call of closest_hit, instance_hit or any_hit about world ray r.
template <class T>
rt::test::served_objects<T> served_for(const std::vector<shape_model<T>>& models,
                                       const std::vector<instance<T>>& instances, const ray<T>& r, long budget = -1) {
    rt::test::served_objects<T> s = served_models(models, budget);
    s.object_rays = object_rays(instances, r);
    return s;
}

// A model placed by an exactly known transform, built flat: every object mapped to the world in
// double, then rounded once to T (spheres need a similarity: their radius scales by its factor).
template <class T>
void place_flat(const shape_model<double>& model, const affine3<double>& m, shape_model<T>& flat) {
    const double size = std::cbrt(std::fabs(glm::determinant(m.linear)));
    auto map = [&](const vec3d& p) { return convert<T>(m.linear * p + m.translation); };
    for (const auto& s : model.spheres) flat.spheres.push_back({map(s.center), T(s.radius * size), s.material});
    for (const auto& t : model.triangles) flat.triangles.push_back({map(t.a), map(t.b), map(t.c), t.material});
}

template <class T>
shape_model<T> convert_model(const shape_model<double>& m) {
    shape_model<T> out;
    for (const auto& s : m.spheres) out.spheres.push_back({convert<T>(s.center), T(s.radius), s.material});
    for (const auto& t : m.triangles) out.triangles.push_back({convert<T>(t.a), convert<T>(t.b), convert<T>(t.c), t.material});
    return out;
}

// The flat answer numbers spheres before triangles; a scene of instances numbers each instance's
// objects together. This is the flat scene in the instances' numbering, one model after the other.
template <class T>
struct flat_scene {
    std::vector<shape_model<T>> parts;  // parts[k]: instance k's objects in the world
    std::vector<int> first;             // the scene number of parts[k]'s object 0

    int count() const { return parts.empty() ? 0 : first.back() + parts.back().count(); }

    // Brute force over every flat object, numbered as the instances number them: chapter 03's loop.
    std::optional<hit_record<T>> closest(const ray<T>& r, const interval<T>& range) const {
        rt::test::served_objects<T> objects;
        objects.count = count();
        objects.test = [this](int n, const ray<T>& ray_, const interval<T>& range_) -> std::optional<hit_record<T>> {
            for (size_t k = 0; k < parts.size(); ++k)
                if (n >= first[k] && n < first[k] + parts[k].count()) return parts[k].test(n - first[k], ray_, range_);
            return std::nullopt;
        };
        return ch03::closest_hit<T>(count(), objects, r, range);
    }

    // How ill-conditioned the hit of object `object` at t is, as a factor on epsilon t: the largest of 1,
    //   distance / size   how far the ray starts from the object (a sphere's centre, a triangle's first
    //                     corner) over its size (radius, longest edge): chapter 07's far sphere, where
    //                     the sphere test's t loses digits;
    //   coordinates / t|d| how large the object's coordinates are against the ray's length to the hit: the
    //                     flat scene's coordinates are rounded to T once, an absolute error of epsilon
    //                     times their size, which moves the hit by that much along the ray.
    T conditioning(int object, const ray<T>& r, T t) const {
        const T reach = t * length(r.direction);
        auto largest = [](const vec3<T>& p) { return std::fmax(std::fabs(p.x), std::fmax(std::fabs(p.y), std::fabs(p.z))); };
        for (size_t k = 0; k < parts.size(); ++k) {
            const int j = object - first[k];
            if (j < 0 || j >= parts[k].count()) continue;
            if (size_t(j) < parts[k].spheres.size()) {
                const sphere<T>& s = parts[k].spheres[size_t(j)];
                return std::fmax(T(1), std::fmax(length(r.origin - s.center) / s.radius, (largest(s.center) + s.radius) / reach));
            }
            const triangle<T>& tri = parts[k].triangles[size_t(j) - parts[k].spheres.size()];
            const T size = std::fmax(length(tri.b - tri.a), std::fmax(length(tri.c - tri.b), length(tri.a - tri.c)));
            const T coordinates = std::fmax(largest(tri.a), std::fmax(largest(tri.b), largest(tri.c)));
            return std::fmax(T(1), std::fmax(length(r.origin - tri.a) / size, coordinates / reach));
        }
        return T(1);
    }
};

// How close the t of a scene built from instances is to the flat one's, for rays that meet a
// surface at a good angle (|cos| >= 0.2): the stated bound, relative to t and to the object's
// conditioning (flat_scene::conditioning), in epsilons (README, "Rounding, measured"):
//     |t_instances - t_flat| <= flat_t_bound_epsilons * epsilon * t * conditioning.
template <class T>
constexpr T flat_t_bound_epsilons = T(16);  // measured largest: 3.9 (README, "Rounding, measured")

// The error of t in epsilons of t * conditioning, for the bound above.
template <class T>
T t_error_epsilons(T got, T want, T conditioning) {
    if (!std::isfinite(got)) return infinity<T>;
    return std::fabs(got - want) / (std::numeric_limits<T>::epsilon() * std::fabs(want) * conditioning);
}

template <class T>
std::string describe_ray(const ray<T>& r) {
    return "ray from " + rt::test::describe(r.origin) + " along " + rt::test::describe(r.direction);
}

}  // namespace rt::ch10::test
