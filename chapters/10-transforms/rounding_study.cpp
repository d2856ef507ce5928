// rounding_study.cpp — a measurement, not an exercise: the rounding a
// transform adds to a hit's t and to its point (README, "Rounding, measured").
//
// For each precision, random placements (a turn, a scale per axis or one
// scale for spheres, a shear for triangles, a translation up to `reach`) of a
// unit sphere and of a triangle; rays from 20 sizes away aimed at the object.
// Each hit is found the instanced way (transform_ray into the object's space,
// chapter 02's or 05's test there, the point brought back by to_world) and
// compared with the exact hit (long double, from the same T inputs: the
// placed object mapped exactly, the ray as given). Reported, in epsilons of
// T: |t - t_exact| / (epsilon t), and the point's error over its
// coordinates' scale (max|o_k| + t max|d_k|), for the point brought back by to_world and for the world ray's
// own r.at(t). Median, 99th percentile and maximum.
//
//   ch10-rounding-study [--rays N]
#include "transform.hpp"

#include "02-sphere/sphere.hpp"
#include "05-triangle/triangle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

namespace {

using namespace rt;
using namespace rt::ch10;
using L = long double;

vec3d random_unit(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    vec3d v;
    do v = vec3d(n(rng), n(rng), n(rng));
    while (!(length(v) > 1e-3));
    return normalize(v);
}

affine3<double> random_placement(std::mt19937_64& rng, bool similarity, double reach) {
    std::uniform_real_distribution<double> s(0.1, 10), h(-1, 1), b(-reach, reach), angle(0, 360);
    affine3<double> shape = similarity ? scale(vec3d(s(rng))) : scale({s(rng), s(rng), s(rng)});
    if (!similarity) {
        affine3<double> shear;
        shear.linear[1][0] = h(rng);
        shear.linear[2][1] = h(rng);
        shape = compose(shear, shape);
    }
    return compose(translate({b(rng), b(rng), b(rng)}), compose(rotate(random_unit(rng), angle(rng)), shape));
}

template <class T>
vec3<L> exact_map(const affine3<T>& m, const vec3<L>& p) {
    return glm::mat<3, 3, L>(m.linear) * p + vec3<L>(m.translation);
}

struct errors {
    std::vector<double> t, point_by_transform, point_by_world_ray;
};

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

// Exact t of the ray (in L) with the triangle (in L): Cramer's rule, no cancellation to speak of at
// 64 bits for the well-conditioned hits kept.
std::optional<L> exact_triangle(const vec3<L>& a, const vec3<L>& b, const vec3<L>& c, const vec3<L>& o, const vec3<L>& d) {
    const vec3<L> e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const L det = glm::dot(e1, p);
    if (det == 0) return std::nullopt;
    const vec3<L> s = o - a;
    const L u = glm::dot(s, p) / det;
    const vec3<L> q = glm::cross(s, e1);
    const L v = glm::dot(d, q) / det;
    if (u < 0 || v < 0 || u + v > 1) return std::nullopt;
    return glm::dot(e2, q) / det;
}

std::optional<L> exact_sphere(const vec3<L>& centre, L radius, const vec3<L>& o, const vec3<L>& d) {
    const vec3<L> f = o - centre;
    const L a = glm::dot(d, d), half_b = glm::dot(f, d);
    // The perpendicular form (chapter 07): radius^2 - |f - (f.d/a) d|^2, no cancellation of |f|^2.
    const vec3<L> perp = f - (half_b / a) * d;
    const L disc = radius * radius - glm::dot(perp, perp);
    if (disc < 0) return std::nullopt;
    const L q = -half_b - std::copysign(std::sqrt(a * disc), half_b);
    const L t0 = glm::dot(f, f) - radius * radius > 0 ? std::min(q / a, (glm::dot(f, f) - radius * radius) / q)
                                                      : std::max(q / a, (glm::dot(f, f) - radius * radius) / q);
    return t0;
}

template <class T>
void measure(bool spheres, int rays, double reach, errors& out) {
    std::mt19937_64 rng(spheres ? 10001 : 10002);
    const T eps = std::numeric_limits<T>::epsilon();
    const triangle<T> tri{{T(-1), T(-1), T(0)}, {T(1), T(-1), T(0)}, {T(0), T(1), T(0)}};
    const sphere<T> ball{vec3<T>(0), T(1)};
    for (int i = 0; i < rays; ++i) {
        const affine3<double> m = random_placement(rng, spheres, reach);
        const placement<T> p = make_placement<T>(m);
        const vec3<L> centre = exact_map(p.to_world, vec3<L>(0));
        const L size = L(glm::length(m.linear[0]));
        const vec3<T> aim = convert<T>(vec3d(centre) + 0.3 * double(size) * random_unit(rng));
        const ray<T> r{convert<T>(vec3d(centre) + 20.0 * double(size) * random_unit(rng)), aim};
        const ray<T> world{r.origin, r.direction - r.origin};
        const vec3<L> o(world.origin), d(world.direction);
        std::optional<L> exact;
        vec3<L> exact_normal;
        if (spheres) {
            exact = exact_sphere(centre, L(ball.radius) * size, o, d);
            if (exact) exact_normal = glm::normalize(o + *exact * d - centre);
        } else {
            const vec3<L> a = exact_map(p.to_world, vec3<L>(tri.a)), b = exact_map(p.to_world, vec3<L>(tri.b)),
                          c = exact_map(p.to_world, vec3<L>(tri.c));
            exact = exact_triangle(a, b, c, o, d);
            exact_normal = glm::normalize(glm::cross(b - a, c - a));
        }
        if (!exact || !(*exact > 0)) continue;
        if (std::fabs(glm::dot(glm::normalize(d), exact_normal)) < L(0.2)) continue;  // good angles only
        const ray<T> object_ray = transform_ray(p.to_object, world);
        const interval<T> range{T(0), infinity<T>};
        const auto h = spheres ? ch02::intersect_sphere(ball, object_ray, range) : ch05::intersect_triangle(tri, object_ray, range);
        if (!h) {
            out.t.push_back(INFINITY);
            continue;
        }
        const vec3<L> exact_point = o + *exact * d;
        // The magnitudes r.at(t) adds up: the origin's and t times the direction's largest components.
        auto largest = [](const vec3<L>& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); };
        const L scale_of_point = largest(o) + *exact * largest(d);
        auto point_error = [&](const vec3<T>& q) {
            return double(glm::length(vec3<L>(q) - exact_point) / (L(eps) * scale_of_point));
        };
        out.t.push_back(double(std::fabs(L(h->t) - *exact) / (L(eps) * *exact)));
        out.point_by_transform.push_back(point_error(transform_ray(p.to_world, ray<T>{h->point, vec3<T>(0)}).origin));
        out.point_by_world_ray.push_back(point_error(world.at(h->t)));
    }
}

void report(const char* precision, const char* shape, const char* what, double reach, const std::vector<double>& v) {
    std::printf("%-6s  %-8s  %-9g  %-26s  %7zu  %9.2f  %9.2f  %9.2f\n", precision, shape, reach, what, v.size(),
                quantile(v, 0.5), quantile(v, 0.99), v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()));
}

template <class T>
void study(const char* precision, int rays) {
    for (bool spheres : {true, false})
        for (double reach : {1.0, 1e3}) {
            errors e;
            measure<T>(spheres, rays, reach, e);
            const char* shape = spheres ? "sphere" : "triangle";
            report(precision, shape, "t", reach, e.t);
            report(precision, shape, "point by to_world", reach, e.point_by_transform);
            report(precision, shape, "point by world r.at(t)", reach, e.point_by_world_ray);
        }
}

}  // namespace

int main(int argc, char** argv) {
    int rays = 20000;
    for (int i = 1; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], "--rays") == 0) rays = std::atoi(argv[i + 1]);
    if (rays < 1) {
        std::fprintf(stderr, "ch10-rounding-study: --rays expects a positive whole number\n");
        return 1;
    }
    std::printf("errors in epsilons of the precision: t as |t - t_exact| / (eps t), points as |p - p_exact| / (eps (max|o_k| + t max|d_k|))\n");
    std::printf("%-6s  %-8s  %-9s  %-26s  %7s  %9s  %9s  %9s\n", "prec", "shape", "reach", "quantity", "hits", "median",
                "p99", "max");
    study<float>("float", rays);
    study<double>("double", rays);
    return 0;
}
