// Hidden tests for chapter 02: a sphere with any centre and radius.
//
// These repeat the public cases with other numbers and add edge cases and
// seeded random rays checked against a long double reference. As for every
// hidden test, a failure names the concept that went wrong and never shows
// the expected values: each check is a bool computed first.
#include "02-sphere/sphere.hpp"

#include "test_support.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace rt;
using rt::ch02::intersect_sphere;

namespace {

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

// Relative closeness; an infinite or NaN value is never near anything (a
// tolerance scaled by |a| would otherwise let a = +inf pass).
template <class T>
bool near(T a, T b, T tol) {
    if (!std::isfinite(a) || !std::isfinite(b)) return false;
    return std::fabs(a - b) <= tol * std::fmax(T(1), std::fmax(std::fabs(a), std::fabs(b)));
}

template <class T>
bool near(const vec3<T>& a, const vec3<T>& b, T tol) {
    return near(a.x, b.x, tol) && near(a.y, b.y, tol) && near(a.z, b.z, tol);
}

template <class T>
T tight() {
    return sizeof(T) == sizeof(float) ? T(1e-5) : T(1e-12);
}

template <class T>
bool hits_at(const std::optional<hit_record<T>>& hit, T t) {
    return hit.has_value() && near(hit->t, t, tight<T>());
}

// ---- the long double reference ---------------------------------------------
//
// The sphere test redone in long double with the numerically stable route:
// the discriminant from the perpendicular distance of the centre to the ray
// (no cancellation between two large squares), and the root pair
// q = -(b + sign(b) sqrt(h)), t = q and c / q (no cancellation in -b + sqrt).
// The distance along the unit direction is converted to t at the end.
struct reference_hit {
    bool hit = false;
    long double t = 0;
    long double h = 0;       // R^2 - (perpendicular distance)^2: how far from grazing
    long double near_t = 0, far_t = 0;
};

template <class T>
reference_hit reference(const sphere<T>& s, const ray<T>& r, long double tmin, long double tmax) {
    reference_hit out;
    const long double ox = (long double)r.origin.x - s.center.x;
    const long double oy = (long double)r.origin.y - s.center.y;
    const long double oz = (long double)r.origin.z - s.center.z;
    const long double dx = r.direction.x, dy = r.direction.y, dz = r.direction.z;
    const long double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(len > 0)) return out;
    const long double ux = dx / len, uy = dy / len, uz = dz / len;
    const long double b = ox * ux + oy * uy + oz * uz;
    const long double px = ox - b * ux, py = oy - b * uy, pz = oz - b * uz;
    const long double perp = std::sqrt(px * px + py * py + pz * pz);
    const long double R = s.radius;
    const long double h = (R - perp) * (R + perp);
    out.h = h;
    if (h < 0) return out;
    const long double dist = std::sqrt(ox * ox + oy * oy + oz * oz);
    const long double c = (dist - R) * (dist + R);
    const long double q = -(b + std::copysign(std::sqrt(h), b));
    long double s0 = q, s1 = (q != 0) ? c / q : 0;
    if (s0 > s1) std::swap(s0, s1);
    out.near_t = s0 / len;
    out.far_t = s1 / len;
    if (tmin < out.near_t && out.near_t < tmax) {
        out.hit = true;
        out.t = out.near_t;
    } else if (tmin < out.far_t && out.far_t < tmax) {
        out.hit = true;
        out.t = out.far_t;
    }
    return out;
}

inline bool close_to_end(long double t, long double tmin, long double tmax, long double scale) {
    return std::fabs(t - tmin) < 1e-3L * scale || std::fabs(t - tmax) < 1e-3L * scale;
}

// Random configurations: spheres anywhere in a box, of radius 0.1 to 5, rays
// from anywhere with directions of length 0.1 to 10. Cases the reference
// calls nearly tangent, or whose roots sit next to the ends of the range, are
// skipped: there float and double may honestly disagree with the reference.
template <class T>
struct random_case {
    sphere<T> s;
    ray<T> r;
    interval<T> range;
    reference_hit ref;
    long double scale = 1;  // |o - C| + R, in units of t: the size of the problem along the ray
};

template <class T>
class case_maker {
public:
    explicit case_maker(unsigned seed) : rng_(seed) {}

    T uniform(T lo, T hi) { return std::uniform_real_distribution<T>(lo, hi)(rng_); }

    vec3<T> point(T extent) { return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)}; }

    vec3<T> direction() {
        vec3<T> d;
        do d = point(T(1));
        while (!(length(d) > T(0.2)) || length(d) > T(1));
        return d * std::exp(uniform(std::log(T(0.1)), std::log(T(10))));
    }

    // inside: put the ray's origin inside the sphere.
    random_case<T> make(bool inside, bool aimed, T tmin = T(0), T tmax = infinity<T>) {
        for (;;) {
            random_case<T> c;
            c.s.center = point(T(10));
            c.s.radius = std::exp(uniform(std::log(T(0.1)), std::log(T(5))));
            if (inside) {
                vec3<T> offset;
                do offset = point(T(1));
                while (!(length(offset) < T(0.9)));
                c.r.origin = c.s.center + offset * c.s.radius;
            } else {
                c.r.origin = point(T(20));
            }
            c.r.direction = direction();
            if (aimed) {
                // Aim at a random point inside the sphere so most of these rays hit.
                vec3<T> target;
                do target = point(T(1));
                while (!(length(target) < T(0.95)));
                vec3<T> to = c.s.center + target * c.s.radius - c.r.origin;
                if (!(length(to) > T(1e-3))) continue;
                c.r.direction = normalize(to) * length(c.r.direction);
            }
            c.range = {tmin, tmax};
            c.ref = reference(c.s, c.r, (long double)tmin, (long double)tmax);
            const long double dlen = std::sqrt((long double)dot(c.r.direction, c.r.direction));
            const long double R = c.s.radius;
            c.scale = ((long double)length(c.r.origin - c.s.center) + R) / dlen;
            // Skip the ill-conditioned: near tangents, origins on the surface, roots at tmin.
            if (std::fabs(c.ref.h) < 1e-2L * R * R) continue;
            const long double on_surface = std::fabs((long double)length(c.r.origin - c.s.center) - R);
            if (on_surface < 1e-2L * R) continue;
            if (c.ref.h > 0 && (close_to_end(c.ref.near_t, tmin, tmax, c.scale) ||
                                close_to_end(c.ref.far_t, tmin, tmax, c.scale)))
                continue;
            return c;
        }
    }

private:
    std::mt19937 rng_;
};

// Tolerance on t, relative to the size of the problem along the ray. It is
// set for the logic of this chapter, not for the numerics of chapter 07: on
// these cases the worst float error of the half-b formula is about 5e-5, of
// the geometric form 7e-5, and of a correct but expanded c = o.o - 2 o.C +
// C.C - R^2 about 1.5e-3 (double: about 1e-13, 1e-13 and 3e-12), so every
// correct formulation passes, while a wrong root is off by far more.
template <class T>
long double t_tolerance() {
    return sizeof(T) == sizeof(float) ? 5e-3L : 1e-10L;
}

template <class T>
bool agrees_with_reference(const random_case<T>& c, const std::optional<hit_record<T>>& hit) {
    if (hit.has_value() != c.ref.hit) return false;
    if (!hit) return true;
    return std::isfinite(hit->t) && std::fabs((long double)hit->t - c.ref.t) <= t_tolerance<T>() * c.scale;
}

// The normal's length is checked against a tolerance that grows with
// (size / R)^2: for a small sphere far away, float loses the radius in
// |o - C|^2 - R^2 (the lecture's 4096 r limit), the point drifts off the
// sphere and (P - C) / R is no longer exactly unit. That is chapter 07's
// subject, not a mistake in this chapter.
template <class T>
bool record_is_consistent(const sphere<T>& s, const ray<T>& r, const hit_record<T>& hit) {
    const T eps = std::numeric_limits<T>::epsilon();
    const T size = length(r.origin - s.center) + s.radius;
    const T tol = T(64) * eps;
    const vec3<T> on_ray = r.at(hit.t);
    const vec3<T> outward = (hit.point - s.center) / s.radius;
    const T spread = size / s.radius;
    return is_finite(hit.point) && is_finite(hit.normal) && length(hit.point - on_ray) <= tol * size &&
           std::fabs(length(hit.normal) - T(1)) <= tol + T(16) * eps * spread * spread &&
           // the direction of P - C: dividing by R and normalising both pass
           length(normalize(hit.normal) - normalize(outward)) <= tol && hit.object == -1;
}

constexpr int random_cases = 4000;

}  // namespace

// ---- the public cases, with other numbers ------------------------------------

TEST_CASE_TEMPLATE("rays passing beside spheres miss them", T, RT_SCALARS) {
    const sphere<T> s{{T(-2), T(1), T(-6)}, T(1.5)};
    const ray<T> beside[] = {
        {{-2, 3, 0}, {0, 0, -1}},       // passes 2 above the centre
        {{0, 0, 0}, {1, 0, 0}},         // goes sideways
        {{-4, 1, -6}, {0, 1, 0}},       // at distance 2, parallel to y
        {{1, 1, 0}, {0, 0, -3}},        // passes 3 to the right, non-unit direction
    };
    bool all_miss = true;
    for (const auto& r : beside) all_miss = all_miss && !intersect_sphere(s, r, ahead<T>()).has_value();
    CHECK_MESSAGE(all_miss, "a ray that passes farther than R from the centre misses (negative discriminant)");
}

TEST_CASE_TEMPLATE("a ray aimed at the centre hits the near side", T, RT_SCALARS) {
    const sphere<T> s{{T(-2), T(1), T(-6)}, T(1.5)};
    const ray<T> r{{-2, 1, 4}, {0, 0, -1}};
    const bool ok = hits_at(intersect_sphere(s, r, ahead<T>()), T(8.5));
    CHECK_MESSAGE(ok, "of the two roots the nearer one is the visible surface");
}

TEST_CASE_TEMPLATE("tangent rays touch at a single point", T, RT_SCALARS) {
    // Exact tangents: the discriminant is exactly zero in float and in double.
    const sphere<T> s{{T(0), T(0), T(0)}, T(2)};
    const ray<T> r1{{2, 0, 5}, {0, 0, -1}};
    const sphere<T> s2{{T(1), T(-1), T(-4)}, T(0.5)};
    const ray<T> r2{{1, T(-0.5), 0}, {0, 0, -2}};
    const bool first = hits_at(intersect_sphere(s, r1, ahead<T>()), T(5));
    const bool second = hits_at(intersect_sphere(s2, r2, ahead<T>()), T(2));
    CHECK_MESSAGE(first, "a discriminant of exactly zero is a (double) root: a tangent ray hits");
    CHECK_MESSAGE(second, "a discriminant of exactly zero is a (double) root: a tangent ray hits");
}

TEST_CASE_TEMPLATE("spheres behind the ray are never hit", T, RT_SCALARS) {
    const sphere<T> s{{T(-2), T(1), T(-6)}, T(1.5)};
    const ray<T> away[] = {
        {{-2, 1, 4}, {0, 0, 1}},
        {{-2, 1, -10}, {0, 0, -1}},
        {{-2, 5, -6}, {0, T(0.5), 0}},
    };
    bool all_miss = true;
    for (const auto& r : away) all_miss = all_miss && !intersect_sphere(s, r, ahead<T>()).has_value();
    CHECK_MESSAGE(all_miss, "roots with t < tmin are behind the ray: a sphere behind the camera must not show up");
}

TEST_CASE_TEMPLATE("from inside the sphere the far root is returned", T, RT_SCALARS) {
    const sphere<T> s{{T(-2), T(1), T(-6)}, T(1.5)};
    const ray<T> r{{-2, T(1.5), -6}, {0, 1, 0}};  // roots t = -2 and t = 1
    const bool ok = hits_at(intersect_sphere(s, r, ahead<T>()), T(1));
    CHECK_MESSAGE(ok, "when the near root is behind the origin, the far root is the hit");
}

TEST_CASE_TEMPLATE("the length of the direction only rescales t", T, RT_SCALARS) {
    const sphere<T> s{{T(-2), T(1), T(-6)}, T(1.5)};
    bool ok = true;
    for (T k : {T(0.25), T(2), T(3), T(1024)}) {
        const ray<T> r{{-2, 1, 4}, {0, 0, -k}};
        auto hit = intersect_sphere(s, r, ahead<T>());
        ok = ok && hits_at(hit, T(8.5) / k) && near(hit->point, vec3<T>(-2, 1, T(-4.5)), tight<T>());
    }
    CHECK_MESSAGE(ok, "a = d . d stays in the quadratic: scaling d divides t and leaves the hit point alone");
}

TEST_CASE_TEMPLATE("centre and radius enter the quadratic", T, RT_SCALARS) {
    // An origin 13 from the centre (5, 12, 0 apart), aimed at it with a unit direction.
    const sphere<T> s{{T(3), T(-4), T(7)}, T(2.5)};
    const vec3<T> d = vec3<T>(-5, -12, 0) / T(13);
    const ray<T> r{{8, 8, 7}, d};
    const bool ok = hits_at(intersect_sphere(s, r, ahead<T>()), T(10.5));
    CHECK_MESSAGE(ok, "substitute the ray into |p - C|^2 = R^2 with this sphere's centre and radius");
}

TEST_CASE_TEMPLATE("normals are outward and of unit length", T, RT_SCALARS) {
    bool unit = true, outward = true, matches = true;
    for (T R : {T(0.25), T(1), T(3), T(40)}) {
        const sphere<T> s{{T(1), T(-2), T(-10)}, R};
        // From four radii away, aimed a third of a radius off the centre.
        const vec3<T> eye = s.center + vec3<T>(0, 0, T(4) * R);
        const ray<T> r{eye, vec3<T>(T(1) + R / T(3), -2, -10) - eye};
        auto hit = intersect_sphere(s, r, ahead<T>());
        if (!hit) {
            unit = outward = matches = false;
            continue;
        }
        const vec3<T> expected = (hit->point - s.center) / R;
        unit = unit && near(length(hit->normal), T(1), T(1e-4));
        outward = outward && dot(hit->normal, hit->point - s.center) > T(0);
        matches = matches && near(hit->normal, expected, T(1e-4));
    }
    CHECK_MESSAGE(unit, "the normal (P - C) / R has length 1: divide by the radius");
    CHECK_MESSAGE(outward, "the normal points out of the sphere: P - C, not C - P");
    CHECK_MESSAGE(matches, "the normal at P is (P - C) / R");
}

TEST_CASE_TEMPLATE("the record holds the point r.at(t)", T, RT_SCALARS) {
    const sphere<T> s{{T(3), T(-4), T(7)}, T(2.5)};
    const ray<T> r{{-1, 1, 2}, {T(1.5), T(-2.0), T(1.25)}};
    auto hit = intersect_sphere(s, r, ahead<T>());
    const bool found = hit.has_value();
    CHECK_MESSAGE(found, "this ray crosses the sphere");
    if (!found) return;
    const bool on_ray = near(hit->point, r.at(hit->t), T(1e-4));
    const bool on_sphere = near(length(hit->point - s.center), s.radius, T(1e-4));
    const bool untouched_index = hit->object == -1;
    CHECK_MESSAGE(on_ray, "the hit point is the ray evaluated at the returned t");
    CHECK_MESSAGE(on_sphere, "the hit point lies on the sphere, R from the centre");
    CHECK_MESSAGE(untouched_index, "intersect_sphere leaves the object index at -1 for the scene loop");
}

TEST_CASE_TEMPLATE("tmin and tmax bound the answer", T, RT_SCALARS) {
    // Roots exactly t = 6 and t = 10 in both precisions.
    const sphere<T> s{{T(1), T(2), T(-3)}, T(2)};
    const ray<T> r{{1, 2, 5}, {0, 0, -1}};
    const bool below = !intersect_sphere(s, r, interval<T>{T(0), T(5.5)}).has_value();
    const bool far_only = hits_at(intersect_sphere(s, r, interval<T>{T(7), T(20)}), T(10));
    const bool gap = !intersect_sphere(s, r, interval<T>{T(6.5), T(9.5)}).has_value();
    const bool above = !intersect_sphere(s, r, interval<T>{T(11), infinity<T>}).has_value();
    CHECK_MESSAGE(below, "roots beyond tmax do not count");
    CHECK_MESSAGE(far_only, "a near root at or below tmin is skipped and the far root is returned");
    CHECK_MESSAGE(gap, "when neither root is inside (tmin, tmax) the answer is a miss");
    CHECK_MESSAGE(above, "roots below tmin do not count");
}

// ---- edge cases ---------------------------------------------------------------

TEST_CASE_TEMPLATE("the interval is open at both ends", T, RT_SCALARS) {
    // Roots exactly t = 6 and t = 10.
    const sphere<T> s{{T(1), T(2), T(-3)}, T(2)};
    const ray<T> r{{1, 2, 5}, {0, 0, -1}};
    const bool tmin_excluded = hits_at(intersect_sphere(s, r, interval<T>{T(6), T(20)}), T(10));
    const bool tmax_excluded = !intersect_sphere(s, r, interval<T>{T(0), T(6)}).has_value();
    const bool both_excluded = !intersect_sphere(s, r, interval<T>{T(6), T(10)}).has_value();
    CHECK_MESSAGE(tmin_excluded, "a root exactly at tmin does not count (tmin < t, strictly)");
    CHECK_MESSAGE(tmax_excluded, "a root exactly at tmax does not count (t < tmax, strictly)");
    CHECK_MESSAGE(both_excluded, "roots exactly at tmin and tmax both fall outside the open interval");
}

TEST_CASE_TEMPLATE("a ray starting on the surface leaving it finds nothing ahead", T, RT_SCALARS) {
    // The origin (1,2,-1) is on the sphere and the ray points outwards: roots t = -4 and t = 0.
    const sphere<T> s{{T(1), T(2), T(-3)}, T(2)};
    const ray<T> out{{1, 2, -1}, {0, 0, 1}};
    const bool none = !intersect_sphere(s, out, ahead<T>()).has_value();
    CHECK_MESSAGE(none, "a ray leaving the surface does not hit it again at t = 0 (tmin < t is strict)");
    // Pointing inwards from the surface: roots t = 0 and t = 4, the far one counts.
    const ray<T> in{{1, 2, -1}, {0, 0, -1}};
    const bool far_one = hits_at(intersect_sphere(s, in, ahead<T>()), T(4));
    CHECK_MESSAGE(far_one, "a ray entering from the surface skips t = 0 and hits the far side");
}

TEST_CASE_TEMPLATE("perspective rays see only beyond the image plane", T, RT_SCALARS) {
    // Eye 0.5 from the near side: entry at t = 0.5 (before the image plane), exit at t = 4.5.
    const sphere<T> s{{T(0), T(0), T(-3)}, T(2)};
    const ray<T> r{{0, 0, T(-0.5)}, {0, 0, -1}};
    const bool ok = hits_at(intersect_sphere(s, r, interval<T>::in_front_of_image_plane()), T(4.5));
    CHECK_MESSAGE(ok, "with t > 1 the entry between eye and image plane is skipped");
}

TEST_CASE_TEMPLATE("a zero direction is a miss", T, RT_SCALARS) {
    const sphere<T> s{{T(0), T(0), T(-3)}, T(2)};
    const ray<T> outside{{0, 0, 5}, {0, 0, 0}};
    const ray<T> inside{{0, 0, -3}, {0, 0, 0}};
    bool ok = !intersect_sphere(s, outside, ahead<T>()).has_value() &&
              !intersect_sphere(s, inside, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a ray with no direction goes nowhere: report a miss, never a NaN");
}

TEST_CASE_TEMPLATE("NaN inputs never produce a hit", T, RT_SCALARS) {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const sphere<T> s{{T(0), T(0), T(-3)}, T(2)};
    const ray<T> bad_origin{{nan, 0, 5}, {0, 0, -1}};
    const ray<T> bad_direction{{0, 0, 5}, {0, nan, -1}};
    const ray<T> good{{0, 0, 5}, {0, 0, -1}};
    const sphere<T> bad_centre{{T(0), nan, T(-3)}, T(2)};
    const sphere<T> bad_radius{{T(0), T(0), T(-3)}, nan};
    bool ok = !intersect_sphere(s, bad_origin, ahead<T>()).has_value() &&
              !intersect_sphere(s, bad_direction, ahead<T>()).has_value() &&
              !intersect_sphere(bad_centre, good, ahead<T>()).has_value() &&
              !intersect_sphere(bad_radius, good, ahead<T>()).has_value();
    CHECK_MESSAGE(ok, "a NaN anywhere makes the discriminant NaN: write the tests so NaN is a miss");
}

TEST_CASE_TEMPLATE("the whole picture can be scaled", T, RT_SCALARS) {
    // Scaling origin, centre and radius by a power of two scales t exactly.
    bool ok = true;
    for (T k : {T(1.0 / 1024), T(1.0 / 8), T(64), T(4096)}) {
        const sphere<T> s{{T(1) * k, T(2) * k, T(-3) * k}, T(2) * k};
        const ray<T> r{{T(1) * k, T(2) * k, T(5) * k}, {0, 0, -1}};
        auto hit = intersect_sphere(s, r, ahead<T>());
        ok = ok && hits_at(hit, T(6) * k) && near(hit->normal, vec3<T>(0, 0, 1), tight<T>());
    }
    CHECK_MESSAGE(ok, "tiny and huge spheres work the same way: t and the point scale, the normal stays unit");
}

TEST_CASE_TEMPLATE("a sphere far from the origin is still hit accurately", T, RT_SCALARS) {
    // A radius-1 sphere 1000 units away along -z, seen from the origin.
    const sphere<T> s{{T(0), T(0), T(-1000)}, T(1)};
    const ray<T> r{{0, 0, 0}, {0, 0, -1}};
    const bool ok = hits_at(intersect_sphere(s, r, ahead<T>()), T(999));
    CHECK_MESSAGE(ok, "the near root of a distant sphere is found (use o - C in the quadratic)");
}

// ---- seeded random rays against a long double reference -----------------------

TEST_CASE_TEMPLATE("random rays from outside agree with a careful reference", T, RT_SCALARS) {
    case_maker<T> make(20261122u);
    int disagreements = 0, hits = 0;
    for (int i = 0; i < random_cases; ++i) {
        const random_case<T> c = make.make(false, i % 2 == 0);
        auto hit = intersect_sphere(c.s, c.r, c.range);
        hits += hit.has_value() ? 1 : 0;
        if (!agrees_with_reference(c, hit)) ++disagreements;
    }
    const bool enough_hits = hits > random_cases / 4;
    const bool ok = disagreements == 0;
    CHECK_MESSAGE(enough_hits, "rays aimed into spheres hit them");
    CHECK_MESSAGE(ok, "hit or miss, and the nearest t in range, agree with a higher-precision computation");
}

TEST_CASE_TEMPLATE("random rays from inside agree with a careful reference", T, RT_SCALARS) {
    case_maker<T> make(7u);
    int disagreements = 0;
    for (int i = 0; i < random_cases; ++i) {
        const random_case<T> c = make.make(true, false);
        if (!agrees_with_reference(c, intersect_sphere(c.s, c.r, c.range))) ++disagreements;
    }
    const bool ok = disagreements == 0;
    CHECK_MESSAGE(ok, "from inside a sphere every ray leaves it through the far root");
}

TEST_CASE_TEMPLATE("random rays with a positive tmin agree with a careful reference", T, RT_SCALARS) {
    case_maker<T> make(31337u);
    int disagreements = 0;
    for (int i = 0; i < random_cases; ++i) {
        const random_case<T> c = make.make(i % 3 == 0, true, make.uniform(T(0.5), T(8)));
        if (!agrees_with_reference(c, intersect_sphere(c.s, c.r, c.range))) ++disagreements;
    }
    const bool ok = disagreements == 0;
    CHECK_MESSAGE(ok, "with tmin > 0 the answer is the first root beyond tmin, as in the reference");
}

TEST_CASE_TEMPLATE("random rays with a finite tmax agree with a careful reference", T, RT_SCALARS) {
    case_maker<T> make(2718u);
    int disagreements = 0;
    for (int i = 0; i < random_cases; ++i) {
        const T tmin = i % 2 == 0 ? T(0) : make.uniform(T(0.5), T(4));
        const random_case<T> c = make.make(i % 3 == 0, true, tmin, tmin + make.uniform(T(1), T(20)));
        if (!agrees_with_reference(c, intersect_sphere(c.s, c.r, c.range))) ++disagreements;
    }
    const bool ok = disagreements == 0;
    CHECK_MESSAGE(ok, "roots beyond tmax do not count: hit or miss and t agree with the reference");
}

TEST_CASE_TEMPLATE("random hits report a consistent record", T, RT_SCALARS) {
    case_maker<T> make(4242u);
    int bad = 0, hits = 0;
    for (int i = 0; i < random_cases; ++i) {
        const random_case<T> c = make.make(i % 4 == 0, true);
        auto hit = intersect_sphere(c.s, c.r, c.range);
        if (!hit) continue;
        ++hits;
        if (!record_is_consistent(c.s, c.r, *hit)) ++bad;
    }
    const bool enough_hits = hits > random_cases / 2;
    const bool ok = bad == 0;
    CHECK_MESSAGE(enough_hits, "rays aimed into spheres hit them");
    CHECK_MESSAGE(ok, "every hit holds point = r.at(t), the outward unit normal (P - C) / R and object -1");
}

TEST_CASE_TEMPLATE("random answers are never NaN or infinite", T, RT_SCALARS) {
    // Here nothing is skipped: grazing rays and origins on the surface included.
    case_maker<T> make(99u);
    bool ok = true;
    for (int i = 0; i < random_cases && ok; ++i) {
        sphere<T> s{make.point(T(10)), make.uniform(T(0.01), T(5))};
        ray<T> r{make.point(T(20)), make.direction()};
        if (i % 5 == 0) {
            // Graze: start beside the sphere at exactly one radius off, parallel to an axis.
            r.origin = s.center + vec3<T>(s.radius, 0, T(10));
            r.direction = {0, 0, -1};
        }
        auto hit = intersect_sphere(s, r, ahead<T>());
        if (hit) ok = std::isfinite(hit->t) && hit->t > T(0) && is_finite(hit->point) && is_finite(hit->normal);
    }
    CHECK_MESSAGE(ok, "a hit always has a finite t inside the range and a finite point and normal");
}

// Catches: c (and half_b) expanded as  o.o - 2 o.C + C.C - R^2  instead of
// computed from oc = o - C first. Every other sphere case puts the ray's
// origin at the world origin, where o = 0 makes the expanded form the same
// numbers as the careful one. Here the sphere sits far from the world origin,
// off every axis, and the ray starts close to it: the expanded squares are
// about |C|^2 (3e11 in float, 3e25 in double) while c itself is 11121, so
// their rounding drowns c. With oc first every number is an exact integer.
TEST_CASE_TEMPLATE("hidden: a sphere far from the world origin, seen from close by, off the axes", T, RT_SCALARS) {
    const T far = sizeof(T) == sizeof(float) ? T(3e5) : T(3e12);
    const vec3<T> centre(far, T(-0.75) * far, T(0.5) * far);
    const sphere<T> s{centre, T(500)};
    // The origin is 511 = 7 * 73 from the centre along (2, 3, 6) / 7: oc = (146, 219, 438).
    const vec3<T> oc(146, 219, 438);
    bool ok = true;
    for (const vec3<T>& d : {vec3<T>(-2, -3, -6), vec3<T>(-1, -3, -5), vec3<T>(T(-0.5), -4, -6)}) {
        const ray<T> r{centre + oc, d};
        const reference_hit ref = reference(s, r, 0.0L, (long double)infinity<T>);
        const auto hit = intersect_sphere(s, r, ahead<T>());
        ok = ok && ref.hit && hit.has_value() &&
             std::fabs((long double)hit->t - ref.t) <= (sizeof(T) == sizeof(float) ? 1e-4L : 1e-10L) * ref.t;
    }
    CHECK_MESSAGE(ok, "a sphere far from the world origin is hit accurately from close by: compute oc = o - C "
                      "first, so the quadratic works with small numbers");
}
