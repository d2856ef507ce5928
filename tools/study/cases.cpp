// cases.cpp — generators of the case families (see cases.hpp).
#include "cases.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <array>
#include <map>
#include <algorithm>

namespace rt::study {
namespace {

// A reproducible stream of numbers: the Mersenne twister is specified
// exactly by the standard, and the mapping to [0, 1) is written here (the
// standard distributions may differ between libraries).
class random_stream {
public:
    explicit random_stream(std::uint64_t seed) : engine_(seed) {}
    double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    vec3d in_box(double half) { return {uniform(-half, half), uniform(-half, half), uniform(-half, half)}; }
    vec3d unit() {
        for (;;) {
            vec3d v = in_box(1);
            double l = length(v);
            if (l > 0.1 && l <= 1) return v / l;
        }
    }

private:
    std::mt19937_64 engine_;
};

// Two unit vectors perpendicular to w and to each other.
void frame(const vec3d& w, vec3d& u, vec3d& v) {
    vec3d helper = std::fabs(w.x) < 0.6 ? vec3d(1, 0, 0) : vec3d(0, 1, 0);
    u = normalize(cross(w, helper));
    v = cross(w, u);
}

std::string label(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

template <class T>
vec3<T> to(const vec3d& v) {
    return convert<T>(v);
}

template <class T>
sphere<T> make_sphere(const vec3d& c, double r) {
    return sphere<T>{to<T>(c), static_cast<T>(r), 0};
}

template <class T>
interval<T> ahead() {
    return {T(0), infinity<T>};
}

// Moves x by k representable numbers (towards +infinity for k > 0).
template <class T>
T nudge(T x, int k) {
    for (int i = 0; i < k; ++i) x = std::nextafter(x, infinity<T>);
    for (int i = 0; i > k; --i) x = std::nextafter(x, -infinity<T>);
    return x;
}

}  // namespace

std::vector<double> far_distances() { return {1e2, 1e3, 4100, 1e4, 1e5, 1e6}; }

template <class T>
family<sphere_query<T>> well_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"well", "random spheres and rays, about half of them hits", {}, {}, {}, {}};
    random_stream rs(o.seed + 1);
    int g = fam.add_group("random");
    for (int i = 0; i < 4 * o.per_group; ++i) {
        vec3d c = rs.in_box(10), origin = rs.in_box(20);
        double r = rs.uniform(0.5, 3);
        vec3d aim = c + rs.unit() * (r * rs.uniform(0, 1.5));
        fam.add({{to<T>(origin), to<T>(aim - origin)}, make_sphere<T>(c, r), ahead<T>()}, g);
    }
    return fam;
}

// Rays across the whole silhouette of a unit sphere D radii away: half of
// them spread over a square 2.4 radii wide, half in a thin band at the rim.
template <class T>
family<sphere_query<T>> far_sphere_family(const case_options& o, const std::vector<double>& distances) {
    family<sphere_query<T>> fam{"far", "unit sphere 1e2..1e6 radii away: axis, orthographic and perspective rays",
                                {}, {}, {}, {}};
    random_stream rs(o.seed + 2);
    auto spot = [&rs](int i) {
        if (i % 2 == 0) return std::pair<double, double>{rs.uniform(-1.2, 1.2), rs.uniform(-1.2, 1.2)};
        double angle = rs.uniform(0, 6.283185307179586), rho = 1 + rs.uniform(-0.01, 0.01);
        return std::pair<double, double>{rho * std::cos(angle), rho * std::sin(angle)};
    };
    for (const char* setup : {"axis", "ortho", "persp"}) {
        for (double D : distances) {
            int g = fam.add_group(std::string(setup) + " " + label(D));
            // A general direction and eye for this group (unused by "axis").
            vec3d w = rs.unit(), u, v, eye = rs.in_box(1);
            frame(w, u, v);
            for (int i = 0; i < o.per_group; ++i) {
                auto [x, y] = spot(i);
                if (setup[0] == 'a') {  // the chapter's own setup: sphere at the origin, rays along -z
                    fam.add({{to<T>(vec3d(x, y, D)), to<T>(vec3d(0, 0, -1))}, make_sphere<T>(vec3d(0), 1), ahead<T>()},
                            g);
                } else if (setup[0] == 'o') {
                    fam.add({{to<T>(eye + x * u + y * v), to<T>(w)}, make_sphere<T>(eye + D * w, 1), ahead<T>()}, g);
                } else {
                    fam.add({{to<T>(eye), to<T>(w + (x * u + y * v) / D)}, make_sphere<T>(eye + D * w, 1), ahead<T>()},
                            g);
                }
            }
        }
    }
    return fam;
}

// A huge sphere seen from just above its surface (the "ground sphere"):
// rays at every elevation, many of them close to the horizon.
template <class T>
family<sphere_query<T>> ground_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"ground", "sphere of radius 1e3..1e6 seen from 0.01..1 above its surface", {}, {}, {}, {}};
    random_stream rs(o.seed + 3);
    const double degree = 3.141592653589793 / 180;
    for (double R : {1e3, 1e4, 1e5, 1e6}) {
        for (double h : {1e-2, 1e-1, 1.0}) {
            int g = fam.add_group("R " + label(R) + " h " + label(h));
            for (int i = 0; i < o.per_group / 2; ++i) {
                double elevation = (i % 2 ? rs.uniform(-90, 5) : rs.uniform(-3, 1)) * degree;
                double azimuth = rs.uniform(0, 360) * degree;
                vec3d d(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                        std::cos(elevation) * std::sin(azimuth));
                vec3d origin(rs.uniform(-0.1, 0.1), h, rs.uniform(-0.1, 0.1));
                fam.add({{to<T>(origin), to<T>(d)}, make_sphere<T>(vec3d(0, -R, 0), R), ahead<T>()}, g);
            }
        }
    }
    // Past the range: a ten-times larger sphere seen from 1e-3.
    {
        int g = fam.add_group("R 1e+07 h 0.001");
        for (int i = 0; i < o.per_group / 2; ++i) {
            double elevation = (i % 2 ? rs.uniform(-90, 5) : rs.uniform(-3, 1)) * degree;
            double azimuth = rs.uniform(0, 360) * degree;
            vec3d d(std::cos(elevation) * std::cos(azimuth), std::sin(elevation), std::cos(elevation) * std::sin(azimuth));
            vec3d origin(rs.uniform(-0.01, 0.01), 1e-3, rs.uniform(-0.01, 0.01));
            fam.add({{to<T>(origin), to<T>(d)}, make_sphere<T>(vec3d(0, -1e7, 0), 1e7), ahead<T>()}, g);
        }
    }
    // The same, tilted: the "up" direction is a general one, so every
    // coordinate of f = o - C is huge and they all cancel together.
    for (double R : {1e4, 1e6}) {
        int g = fam.add_group("tilted R " + label(R) + " h 0.01");
        vec3d up = rs.unit(), u, v;
        frame(up, u, v);
        for (int i = 0; i < o.per_group / 2; ++i) {
            double elevation = (i % 2 ? rs.uniform(-90, 5) : rs.uniform(-3, 1)) * degree;
            double azimuth = rs.uniform(0, 360) * degree;
            vec3d d = std::sin(elevation) * up + std::cos(elevation) * (std::cos(azimuth) * u + std::sin(azimuth) * v);
            vec3d origin = 0.01 * up + rs.uniform(-0.1, 0.1) * u;
            fam.add({{to<T>(origin), to<T>(d)}, make_sphere<T>(-R * up, R), ahead<T>()}, g);
        }
    }
    return fam;
}

// Rays within a few ULPs of tangency, on both sides: a tangent ray is built
// in double, rounded, and its origin moved k ULPs (-8..8) across the tangent.
template <class T>
family<sphere_query<T>> grazing_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"grazing", "rays within 8 ULPs of tangency, both sides", {}, {}, {}, {}};
    random_stream rs(o.seed + 4);
    int g = fam.add_group("random spheres");
    for (int i = 0; i < 2 * o.per_group; ++i) {
        vec3d c = rs.in_box(5), w = rs.unit(), u, v;
        frame(w, u, v);
        double r = rs.uniform(0.5, 2), ang = rs.uniform(0, 6.283185307179586);
        vec3d n = std::cos(ang) * u + std::sin(ang) * v;  // unit, perpendicular to w
        vec3d origin = c + r * n - rs.uniform(2, 10) * w;
        ray<T> ry{to<T>(origin), to<T>(w * rs.uniform(0.5, 2))};
        int k = i % 17 - 8;
        // Nudge the coordinate along which n is largest, outwards for k > 0.
        int axis = std::fabs(n.x) > std::fabs(n.y) ? (std::fabs(n.x) > std::fabs(n.z) ? 0 : 2)
                                                   : (std::fabs(n.y) > std::fabs(n.z) ? 1 : 2);
        int steps = (axis == 0 ? n.x : axis == 1 ? n.y : n.z) > 0 ? k : -k;
        T& coord = axis == 0 ? ry.origin.x : axis == 1 ? ry.origin.y : ry.origin.z;
        coord = nudge(coord, steps);
        fam.add({ry, make_sphere<T>(c, r), ahead<T>()}, g);
    }
    int ga = fam.add_group("unit sphere, axis");
    for (int k = -8; k <= 8; ++k) {
        fam.add({{vec3<T>(0, nudge(T(1), k), 5), vec3<T>(0, 0, -1)}, sphere<T>{}, ahead<T>()}, ga);
        fam.add({{vec3<T>(nudge(T(-1), k), 0, -3), vec3<T>(0, 0, 2)}, sphere<T>{}, ahead<T>()}, ga);
        fam.add({{vec3<T>(nudge(T(0.6), k), T(0.8), 7), vec3<T>(0, 0, -1)}, sphere<T>{}, ahead<T>()}, ga);
    }
    return fam;
}

template <class T>
family<sphere_query<T>> origin_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"origin", "ray origin on the surface (out, in), inside, at the centre", {}, {}, {}, {}};
    random_stream rs(o.seed + 5);
    int out = fam.add_group("on surface outward"), in = fam.add_group("on surface inward"),
        inside = fam.add_group("inside"), centre = fam.add_group("at centre");
    for (int i = 0; i < o.per_group; ++i) {
        vec3d c = rs.in_box(10), n = rs.unit(), u, v;
        frame(n, u, v);
        double r = rs.uniform(0.5, 3);
        vec3d tangential = rs.uniform(-0.9, 0.9) * u + rs.uniform(-0.9, 0.9) * v;
        vec3d p = c + r * n;
        fam.add({{to<T>(p), to<T>(n + tangential)}, make_sphere<T>(c, r), ahead<T>()}, out);
        fam.add({{to<T>(p), to<T>(-n + tangential)}, make_sphere<T>(c, r), ahead<T>()}, in);
        fam.add({{to<T>(c + rs.uniform(0, 0.99) * r * rs.unit()), to<T>(rs.unit())}, make_sphere<T>(c, r), ahead<T>()},
                inside);
        sphere<T> s = make_sphere<T>(c, r);
        fam.add({{s.center, to<T>(rs.unit() * rs.uniform(0.5, 2))}, s, ahead<T>()}, centre);
    }
    return fam;
}

// The same well-conditioned scenes shrunk or blown up until r^2 underflows
// or overflows, and with direction lengths 1e-3 and 1e6.
template <class T>
family<sphere_query<T>> scale_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"scale", "tiny and huge radii (squares under/overflow), direction lengths 1e-3 and 1e6",
                                {}, {}, {}, {}};
    random_stream rs(o.seed + 6);
    std::vector<double> scales = sizeof(T) == 4 ? std::vector<double>{1e-25, 1e-20, 1e20, 1e25}
                                                : std::vector<double>{1e-170, 1e-160, 1e160, 1e170};
    for (double s : scales) {
        int g = fam.add_group("scene x " + label(s));
        for (int i = 0; i < o.per_group / 2; ++i) {
            vec3d c = rs.in_box(10), origin = rs.in_box(20);
            double r = rs.uniform(0.5, 3);
            vec3d aim = c + rs.unit() * (r * rs.uniform(0, 1.5));
            fam.add({{to<T>(s * origin), to<T>(aim - origin)}, make_sphere<T>(s * c, s * r), ahead<T>()}, g);
        }
    }
    for (double len : {1e-3, 1e6}) {
        int g = fam.add_group("|d| " + label(len));
        for (int i = 0; i < o.per_group / 2; ++i) {
            vec3d c = rs.in_box(10), origin = rs.in_box(20);
            double r = rs.uniform(0.5, 3);
            vec3d aim = c + rs.unit() * (r * rs.uniform(0, 1.5));
            fam.add({{to<T>(origin), to<T>(normalize(aim - origin) * len)}, make_sphere<T>(c, r), ahead<T>()}, g);
        }
    }
    return fam;
}

// Secondary rays: shadow and reflection rays start on a surface. The hit
// point is rounded to T, so the origin lies a hair inside or outside the
// sphere, and the ray leaves it (or, for a refraction, enters it). Spheres of
// ordinary size, and the ground sphere of radius 1e6 off the world's origin.
template <class T>
family<sphere_query<T>> secondary_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"secondary", "origins on the surface (rounded), leaving it: shadow and reflection rays",
                                {}, {}, {}, {}};
    random_stream rs(o.seed + 8);
    for (const char* kind : {"unit-size leaving", "unit-size entering", "ground 1e6 leaving"}) {
        int g = fam.add_group(kind);
        for (int i = 0; i < o.per_group; ++i) {
            const bool ground = kind[0] == 'g';
            vec3d c = ground ? vec3d(rs.uniform(-100, 100), -1e6, rs.uniform(-100, 100)) : rs.in_box(10);
            double r = ground ? 1e6 : rs.uniform(0.5, 3);
            // A surface point near the top for the ground, anywhere otherwise.
            vec3d n = ground ? normalize(vec3d(rs.uniform(-1e-4, 1e-4), 1, rs.uniform(-1e-4, 1e-4))) : rs.unit();
            vec3d u, v;
            frame(n, u, v);
            vec3d tangential = rs.uniform(-0.95, 0.95) * u + rs.uniform(-0.95, 0.95) * v;
            vec3d d = (kind[10] == 'e' ? -n : n) + tangential;
            fam.add({{to<T>(c + r * n), to<T>(d)}, make_sphere<T>(c, r), ahead<T>()}, g);
        }
    }
    return fam;
}

// Spheres at the limits of the format: radius and distances near the
// smallest and largest normal numbers whose squares (and products of four)
// leave the range, and non-zero subnormal directions.
template <class T>
family<sphere_query<T>> limits_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"limits", "radius 1e-30..1e30 (float), 1e-200..1e300 (double); subnormal directions",
                                {}, {}, {}, {}};
    random_stream rs(o.seed + 9);
    std::vector<double> scales = sizeof(T) == 4 ? std::vector<double>{1e-36, 1e-30, 1e30, 1e36}
                                                : std::vector<double>{1e-300, 1e-200, 1e200, 1e300};
    for (double s : scales) {
        int g = fam.add_group("scene x " + label(s));
        for (int i = 0; i < o.per_group / 2; ++i) {
            vec3d c = rs.in_box(1), origin = rs.in_box(2);
            double r = rs.uniform(0.2, 0.6);
            vec3d aim = c + rs.unit() * (r * rs.uniform(0, 1.5));
            fam.add({{to<T>(s * origin), to<T>(aim - origin)}, make_sphere<T>(s * c, s * r), ahead<T>()}, g);
        }
    }
    const double sub = std::ldexp(1.0, std::numeric_limits<T>::min_exponent - 8);  // subnormal in T
    int g = fam.add_group("subnormal direction");
    for (int i = 0; i < o.per_group / 2; ++i) {
        vec3d c = rs.in_box(1), origin = rs.in_box(2);
        double r = rs.uniform(0.2, 0.6);
        vec3d aim = c + rs.unit() * (r * rs.uniform(0, 1.5));
        // A small scene so that t = |aim - origin| / |d| stays representable.
        const double s = std::ldexp(1.0, std::numeric_limits<T>::min_exponent + 40);
        fam.add({{to<T>(s * origin), to<T>(normalize(aim - origin) * sub)}, make_sphere<T>(s * c, s * r), ahead<T>()},
                g);
    }
    return fam;
}

// Huge spheres whose centre is NOT straight below the origin along an axis:
// a random centre, the origin 0.01..1 above a random point of the surface,
// so every coordinate of f = o - C is large and c cancels in all three.
template <class T>
family<sphere_query<T>> offaxis_sphere_family(const case_options& o) {
    family<sphere_query<T>> fam{"offaxis", "ground spheres 1e4..1e6 with a general centre, origin 0.01..1 above",
                                {}, {}, {}, {}};
    random_stream rs(o.seed + 10);
    const double degree = 3.141592653589793 / 180;
    for (double R : {1e4, 1e6}) {
        for (double h : {1e-2, 1.0}) {
            int g = fam.add_group("R " + label(R) + " h " + label(h));
            for (int i = 0; i < o.per_group / 2; ++i) {
                vec3d c = rs.in_box(1000), up = rs.unit(), u, v;
                frame(up, u, v);
                double elevation = (i % 2 ? rs.uniform(-90, 5) : rs.uniform(-3, 1)) * degree;
                double azimuth = rs.uniform(0, 360) * degree;
                vec3d d = std::sin(elevation) * up + std::cos(elevation) * (std::cos(azimuth) * u + std::sin(azimuth) * v);
                fam.add({{to<T>(c + (R + h) * up), to<T>(d)}, make_sphere<T>(c, R), ahead<T>()}, g);
            }
        }
    }
    return fam;
}

// Named cases: invalid input and the edges of the range rule.
template <class T>
family<sphere_query<T>> special_sphere_family() {
    family<sphere_query<T>> fam{"special", "NaN and infinite input, zero direction, subnormals, t at tmax, t = -0",
                                {}, {}, {}, {}};
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>, tiny = std::numeric_limits<T>::denorm_min();
    const T sub = std::numeric_limits<T>::min() / T(4);  // a subnormal number
    auto add = [&fam](const std::string& name, vec3<T> o, vec3<T> d, sphere<T> s, interval<T> range) {
        fam.add({{o, d}, s, range}, fam.add_group(name));
    };
    sphere<T> unit{};
    add("NaN origin", {nan, 0, 5}, {0, 0, -1}, unit, ahead<T>());
    add("NaN direction", {0, 0, 5}, {0, nan, -1}, unit, ahead<T>());
    add("NaN centre", {0, 0, 5}, {0, 0, -1}, {{0, nan, 0}, 1, 0}, ahead<T>());
    add("NaN radius", {0, 0, 5}, {0, 0, -1}, {{0, 0, 0}, nan, 0}, ahead<T>());
    add("NaN tmax", {0, 0, 5}, {0, 0, -1}, unit, {T(0), nan});
    add("infinite origin", {0, 0, inf}, {0, 0, -1}, unit, ahead<T>());
    add("infinite direction", {0, 0, 5}, {0, 0, -inf}, unit, ahead<T>());
    add("infinite radius", {0, 0, 5}, {0, 0, -1}, {{0, 0, 0}, inf, 0}, ahead<T>());
    add("zero direction", {0, 0, 5}, {0, 0, 0}, unit, ahead<T>());
    add("zero direction inside, range from -1", {0, 0, 0}, {0, 0, 0}, unit, {T(-1), inf});
    // t = (1/1024) / sub: huge but representable.
    add("subnormal direction", {0, 0, T(1) + T(1) / T(1024)}, {0, 0, -sub}, unit, ahead<T>());
    add("subnormal origin coordinates", {sub, tiny, 5}, {0, 0, -1}, unit, ahead<T>());
    add("subnormal radius", {0, 0, 4 * sub}, {0, 0, -1}, {{0, 0, 0}, sub, 0}, ahead<T>());
    add("hit exactly at tmax", {0, 0, 5}, {0, 0, -1}, unit, {T(0), T(4)});
    add("roots exactly at tmin and tmax", {0, 0, 5}, {0, 0, -1}, unit, {T(4), T(6)});
    add("origin on surface outward (t = 0 or -0)", {0, 0, 1}, {0, 0, 1}, unit, ahead<T>());
    add("origin on surface outward, range from -0", {0, 0, 1}, {0, 0, 1}, unit, {-T(0), inf});
    add("origin on surface inward", {0, 0, 1}, {0, 0, -1}, unit, ahead<T>());
    add("origin at centre", {0, 0, 0}, {0, 0, 1}, unit, ahead<T>());
    add("exact tangent", {0, 1, 5}, {0, 0, -1}, unit, ahead<T>());
    add("sphere behind", {0, 0, 5}, {0, 0, 1}, unit, ahead<T>());
    add("primary ray, image plane at t = 1", {0, 0, 0}, {0, 0, -1}, {{0, 0, -5}, 1, 0}, {T(1), inf});
    // Finite inputs near T's largest number M, whose o - C overflows (the
    // first two) or nearly does: the exact hits are t = M, t = 2 - 1/(2
    // sqrt 3) and t = M/2.
    const T M = std::numeric_limits<T>::max();
    add("o - C beyond the largest number, t = M", {0, 0, -M}, {0, 0, 1}, {{0, 0, M}, M, 0}, ahead<T>());
    add("o - C beyond the largest number, diagonal", {-M, -M, -M}, {M, M, M}, {{M, M, M}, M / 2, 0}, ahead<T>());
    add("o and C near the largest number, t = M/2", {0, 0, -M / 2}, {0, 0, 1}, {{0, 0, M / 4}, M / 4, 0},
        ahead<T>());
    return fam;
}

template <class T>
std::vector<family<sphere_query<T>>> sphere_families(const case_options& o) {
    std::vector<family<sphere_query<T>>> all;
    all.push_back(well_sphere_family<T>(o));
    all.push_back(far_sphere_family<T>(o, far_distances()));
    all.push_back(ground_sphere_family<T>(o));
    all.push_back(grazing_sphere_family<T>(o));
    all.push_back(origin_sphere_family<T>(o));
    all.push_back(scale_sphere_family<T>(o));
    all.push_back(secondary_sphere_family<T>(o));
    all.push_back(limits_sphere_family<T>(o));
    all.push_back(offaxis_sphere_family<T>(o));
    all.push_back(special_sphere_family<T>());
    return all;
}

template <class T>
std::vector<family<plane_query<T>>> plane_families(const case_options& o) {
    std::vector<family<plane_query<T>>> all;
    random_stream rs(o.seed + 7);
    family<plane_query<T>> well{"plane well", "random planes and rays", {}, {}, {}, {}};
    int g = well.add_group("random");
    for (int i = 0; i < 2 * o.per_group; ++i) {
        plane<T> p{to<T>(rs.in_box(10)), to<T>(rs.in_box(1)), 0};
        well.add({{to<T>(rs.in_box(20)), to<T>(rs.in_box(1))}, p, ahead<T>()}, g);
    }
    all.push_back(std::move(well));

    family<plane_query<T>> stiff{"plane stiff", "parallel, in the plane, nearly parallel, far grazing, large offset",
                                 {}, {}, {}, {}};
    const T nan = std::numeric_limits<T>::quiet_NaN(), sub = std::numeric_limits<T>::min() / T(8);
    plane<T> ground{{0, 0, 0}, {0, 1, 0}, 0};
    int par = stiff.add_group("parallel"), lying = stiff.add_group("lying in the plane"),
        near = stiff.add_group("nearly parallel (subnormal n.d)"), far = stiff.add_group("far grazing hit"),
        offset = stiff.add_group("large plane offset"), bad = stiff.add_group("invalid input");
    for (int i = 0; i < o.per_group / 4; ++i) {
        vec3d dir(rs.uniform(-1, 1), 0, rs.uniform(-1, 1));
        stiff.add({{to<T>(vec3d(rs.uniform(-5, 5), rs.uniform(0.1, 5), 0)), to<T>(dir)}, ground, ahead<T>()}, par);
        stiff.add({{to<T>(vec3d(rs.uniform(-5, 5), 0, rs.uniform(-5, 5))), to<T>(dir)}, ground, ahead<T>()}, lying);
        // n.d is a subnormal number; the origin is a few subnormals above the
        // plane so that the hit is at a moderate t.
        T k = static_cast<T>(1 + i % 7);
        stiff.add({{vec3<T>(T(rs.uniform(-1, 1)), k * sub, 0), vec3<T>(1, -sub, 0)}, ground, ahead<T>()}, near);
        double L = std::pow(10.0, rs.uniform(3, 6));
        stiff.add({{to<T>(vec3d(0, 1, 0)), to<T>(vec3d(1, -1 / L, rs.uniform(-0.1, 0.1)))}, ground, ahead<T>()}, far);
        vec3d q = vec3d(1e6, 1e6, 1e6) + rs.in_box(1e5), n = rs.unit();
        vec3d origin = rs.in_box(10), toward = q + 100.0 * cross(n, rs.unit()) - origin;
        stiff.add({{to<T>(origin), to<T>(toward)}, plane<T>{to<T>(q), to<T>(n), 0}, ahead<T>()}, offset);
    }
    stiff.add({{vec3<T>(0, 1, 0), vec3<T>(0, nan, 0)}, ground, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 1, 0), vec3<T>(0, -1, 0)}, plane<T>{{0, 0, 0}, {0, nan, 0}, 0}, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 1, 0), vec3<T>(0, 0, 0)}, ground, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 1, 0), vec3<T>(0, -infinity<T>, 0)}, ground, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 1, 0), vec3<T>(0, -1, 0)}, ground, {T(0), T(1)}}, bad);  // hit exactly at tmax
    stiff.add({{vec3<T>(0, 0, 0), vec3<T>(0, -1, 1)}, ground, ahead<T>()}, bad);    // t = 0 (or -0)
    all.push_back(std::move(stiff));
    return all;
}

// Rays aimed at the shared edges and corners of closed convex meshes
// (icosahedra, subdivided once: 80 triangles). Each ray comes from outside
// and heads for the inside, so its line must cross the surface at the
// point aimed at: one of the triangles around that edge or corner has to
// report a hit. The queries pair each ray with those triangles.
template <class T>
family<triangle_query<T>> edge_triangle_family(const case_options& o) {
    family<triangle_query<T>> fam{"tri edges", "rays through shared edges and corners of closed meshes", {}, {}, {}, {}};
    random_stream rs(o.seed + 8);
    // The icosahedron, then each face split into four, pushed onto the sphere.
    const double p = (1 + std::sqrt(5.0)) / 2;
    std::vector<vec3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                            {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (auto& x : v) x = normalize(x);
    std::vector<std::array<int, 3>> fine;
    auto midpoint = [&v](int a, int b) {
        v.push_back(normalize(v[a] + v[b]));
        return static_cast<int>(v.size()) - 1;
    };
    std::map<std::pair<int, int>, int> cache;
    auto mid = [&](int a, int b) {
        auto key = std::minmax(a, b);
        auto it = cache.find(key);
        if (it != cache.end()) return it->second;
        return cache[key] = midpoint(a, b);
    };
    for (auto f : faces) {
        int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
        fine.push_back({f[0], ab, ca});
        fine.push_back({f[1], bc, ab});
        fine.push_back({f[2], ca, bc});
        fine.push_back({ab, bc, ca});
    }
    int ray_count = 0;
    for (double distance : {0.0, 10.0, 1e3}) {
        vec3d centre = distance == 0 ? vec3d(0) : distance * rs.unit();
        double radius = rs.uniform(0.5, 2);
        std::vector<vec3<T>> vt;  // the mesh's vertices, rounded once: neighbours share them exactly
        for (const auto& x : v) vt.push_back(to<T>(centre + radius * x));
        vec3d centre_t = convert<double>(to<T>(centre));
        int g_edge = fam.add_group("edges, mesh at " + label(distance)),
            g_vertex = fam.add_group("corners, mesh at " + label(distance));
        for (int i = 0; i < o.per_group; ++i) {
            bool corner = i % 4 == 3;
            const auto& f = fine[static_cast<std::size_t>(i * 7) % fine.size()];
            int k = i % 3, a = f[k], b = f[(k + 1) % 3];
            vec3<T> target = corner ? vt[a] : to<T>(convert<double>(vt[a]) + rs.uniform(0.1, 0.9) *
                                                                            (convert<double>(vt[b]) - convert<double>(vt[a])));
            vec3d out = convert<double>(target) - centre_t;
            vec3d u, w;
            frame(normalize(out), u, w);
            vec3d origin = convert<double>(target) + rs.uniform(1, 5) * out + 0.2 * radius * (rs.uniform(-1, 1) * u + rs.uniform(-1, 1) * w);
            ray<T> r{to<T>(origin), to<T>(convert<double>(target) - origin)};
            for (const auto& t : fine) {
                bool has_a = t[0] == a || t[1] == a || t[2] == a, has_b = t[0] == b || t[1] == b || t[2] == b;
                bool shares_edge = corner ? has_a : (has_a && has_b);
                if (!shares_edge) continue;
                fam.add({r, triangle<T>{vt[t[0]], vt[t[1]], vt[t[2]], 0}, ahead<T>()}, corner ? g_vertex : g_edge,
                        ray_count);
            }
            ++ray_count;
        }
    }
    return fam;
}

template <class T>
std::vector<family<triangle_query<T>>> triangle_families(const case_options& o) {
    std::vector<family<triangle_query<T>>> all;
    random_stream rs(o.seed + 9);
    family<triangle_query<T>> well{"tri well", "random triangles and rays", {}, {}, {}, {}};
    int g = well.add_group("random");
    for (int i = 0; i < 2 * o.per_group; ++i) {
        vec3d a = rs.in_box(5), b = rs.in_box(5), c = rs.in_box(5), origin = rs.in_box(10);
        double u = rs.uniform(-0.3, 1), v = rs.uniform(-0.3, 1);
        vec3d aim = a + u * (b - a) + v * (c - a);
        well.add({{to<T>(origin), to<T>(aim - origin)}, triangle<T>{to<T>(a), to<T>(b), to<T>(c), 0}, ahead<T>()}, g);
    }
    all.push_back(std::move(well));
    all.push_back(edge_triangle_family<T>(o));

    family<triangle_query<T>> stiff{"tri stiff", "needle, tiny, far and degenerate triangles, ray in the plane",
                                    {}, {}, {}, {}};
    int needle = stiff.add_group("needle"), tiny = stiff.add_group("tiny"), far = stiff.add_group("far"),
        degenerate = stiff.add_group("degenerate"), in_plane = stiff.add_group("ray in the plane"),
        bad = stiff.add_group("invalid input");
    auto aimed = [&rs](const vec3d& a, const vec3d& b, const vec3d& c, const vec3d& origin) {
        double u = rs.uniform(-0.2, 1), v = rs.uniform(-0.2, 1 - u + 0.2);
        return a + u * (b - a) + v * (c - a) - origin;
    };
    for (int i = 0; i < o.per_group / 4; ++i) {
        vec3d a = rs.in_box(2), e = rs.unit(), origin = rs.in_box(10);
        vec3d b = a + 1e-5 * rs.unit(), c = a + 3.0 * e;
        stiff.add({{to<T>(origin), to<T>(aimed(a, b, c, origin))}, triangle<T>{to<T>(a), to<T>(b), to<T>(c), 0}, ahead<T>()},
                  needle);
        vec3d ta = rs.in_box(1), tb = ta + 1e-6 * rs.unit(), tc = ta + 1e-6 * rs.unit();
        stiff.add({{to<T>(origin), to<T>(aimed(ta, tb, tc, origin))}, triangle<T>{to<T>(ta), to<T>(tb), to<T>(tc), 0},
                   ahead<T>()},
                  tiny);
        vec3d fa = std::pow(10.0, rs.uniform(4, 6)) * rs.unit(), fb = fa + rs.unit(), fc = fa + rs.unit();
        vec3d fo = rs.in_box(1);
        stiff.add({{to<T>(fo), to<T>(aimed(fa, fb, fc, fo))}, triangle<T>{to<T>(fa), to<T>(fb), to<T>(fc), 0}, ahead<T>()},
                  far);
        T s = static_cast<T>(1 + i % 5);
        stiff.add({{to<T>(origin), to<T>(rs.in_box(1) - origin)}, triangle<T>{{0, 0, 0}, {s, s, s}, {2 * s, 2 * s, 2 * s}, 0},
                   ahead<T>()},
                  degenerate);
        stiff.add({{to<T>(vec3d(rs.uniform(-3, -2), rs.uniform(-0.5, 0.5), 0)), to<T>(vec3d(1, rs.uniform(-0.2, 0.2), 0))},
                   triangle<T>{{0, -1, 0}, {1, 0, 0}, {0, 1, 0}, 0}, ahead<T>()},
                  in_plane);
    }
    const T nan = std::numeric_limits<T>::quiet_NaN();
    triangle<T> unit{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0};
    stiff.add({{vec3<T>(0, 0, 5), vec3<T>(nan, 0, -1)}, unit, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 0, 5), vec3<T>(0, 0, 0)}, unit, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 0, 5), vec3<T>(0, 0, -1)}, triangle<T>{{nan, -1, 0}, {1, -1, 0}, {0, 1, 0}, 0}, ahead<T>()},
              bad);
    stiff.add({{vec3<T>(0, 0, 5), vec3<T>(0, 0, -infinity<T>)}, unit, ahead<T>()}, bad);
    stiff.add({{vec3<T>(0, 0, 5), vec3<T>(0, 0, -1)}, unit, {T(0), T(5)}}, bad);  // hit exactly at tmax
    stiff.add({{vec3<T>(0, 0, 0), vec3<T>(0, 0, 1)}, unit, ahead<T>()}, bad);     // t = 0 (or -0)
    all.push_back(std::move(stiff));
    return all;
}

#define RT_INSTANTIATE(T)                                                                                       \
    template family<sphere_query<T>> well_sphere_family<T>(const case_options&);                               \
    template family<sphere_query<T>> far_sphere_family<T>(const case_options&, const std::vector<double>&);     \
    template family<sphere_query<T>> ground_sphere_family<T>(const case_options&);                             \
    template family<sphere_query<T>> grazing_sphere_family<T>(const case_options&);                            \
    template family<sphere_query<T>> origin_sphere_family<T>(const case_options&);                             \
    template family<sphere_query<T>> scale_sphere_family<T>(const case_options&);                              \
    template family<sphere_query<T>> special_sphere_family<T>();                                                \
    template std::vector<family<sphere_query<T>>> sphere_families<T>(const case_options&);                     \
    template std::vector<family<plane_query<T>>> plane_families<T>(const case_options&);                       \
    template family<triangle_query<T>> edge_triangle_family<T>(const case_options&);                           \
    template std::vector<family<triangle_query<T>>> triangle_families<T>(const case_options&);
RT_INSTANTIATE(float)
RT_INSTANTIATE(double)
#undef RT_INSTANTIATE

}  // namespace rt::study
