// worked_values.cpp — prints the README's worked numbers (README, "The worked numbers").
//
// The float columns are the lecture's formulas evaluated in float, one
// rounding per operation as written. The "exact" values are either exact by
// construction (dyadic inputs, computed in long double, where these sums and
// products need no rounding) or come from your intersect_sphere_robust in
// long double, as the chapter program's --error does: with the stubs the
// program stops there, politely.
#include "robust_sphere.hpp"

#include "common/stub.hpp"

#include <cmath>
#include <cstdio>

namespace {

using namespace rt;
using ld = long double;

// The lecture's huge ground: radius 1e6, top at y = 0, the ray from 1 unit above.
const sphere<float> ground{{0, -1e6f, 0}, 1e6f};
const vec3<float> eye{0, 1, 0};

ld exact_root(const vec3<float>& direction) {
    const sphere<ld> s{convert<ld>(ground.center), ld(ground.radius)};
    auto hit = ch07::intersect_sphere_robust(s, ray<ld>{convert<ld>(eye), convert<ld>(direction)}, {0, infinity<ld>});
    return hit ? hit->t : std::nan("");
}

// Chapter 02's near root in float (its discriminant too), and the stable
// pair's in float from a given c and quarter discriminant.
float plain_near_root(float a, float half_b, float c) { return (-half_b - std::sqrt(half_b * half_b - a * c)) / a; }
float stable_near_root(float half_b, float c, float quarter_disc) {
    const float q = -(half_b + std::copysign(std::sqrt(quarter_disc), half_b));
    return c / q;  // half_b < 0 here: c / q is the near root
}

void far_sphere() {
    // Trap 1: a unit sphere 4100 away, the orthographic ray from x = 0.75 along -z.
    const float fx = 0.75f, fz = 4100.0f;
    const float ff = fx * fx + fz * fz, c = ff - 1.0f, hb2 = fz * fz, disc = hb2 - c;
    std::printf("trap 1 (unit sphere 4100 away, ray at x = 0.75):\n");
    std::printf("  f.f       exact %.4Lf  float %.1f\n", ld(fx) * fx + ld(fz) * fz, double(ff));
    std::printf("  c         exact %.4Lf  float %.1f\n", ld(fx) * fx + ld(fz) * fz - 1, double(c));
    std::printf("  half_b^2  exact %.1Lf  float %.1f\n", ld(fz) * fz, double(hb2));
    std::printf("  disc/4    exact %.4Lf  float %.1f\n", ld(fz) * fz - (ld(fx) * fx + ld(fz) * fz - 1), double(disc));
    // Chapter 02's discriminant in float for rays from x = 0 outwards, in steps of 2^-10.
    float x = 0;
    while (x * x + fz * fz - 1.0f <= fz * fz && x < 4) x += 1.0f / 1024;  // disc/4 = half_b^2 - c >= 0
    const float x101 = 1.01f, c101 = x101 * x101 + fz * fz - 1.0f;
    std::printf("  chapter 02's disc/4 is >= 0 (a hit) for every ray with x below %.4f (the sphere's radius is 1);\n"
                "  at x = 1.01 it is %.1f, a hit at t = %.1f\n",
                double(x), double(fz * fz - c101), double(fz - std::sqrt(fz * fz - c101)));
}

void huge_ground() {
    const vec3<float> d{0, -0.125f, -1};
    const vec3<float> f = eye - ground.center;
    const float a = dot(d, d), half_b = dot(f, d), c_float = dot(f, f) - ground.radius * ground.radius;
    // f, a and half_b are exact in float here; in long double so are their products.
    const ld c_exact = ld(f.y) * f.y - ld(ground.radius) * ground.radius;
    const float c_rounded = float(c_exact);  // the float nearest the exact c
    const float disc = float(ld(half_b) * half_b - ld(a) * c_exact);  // fix 1's quarter discriminant, rounded once
    std::printf("traps 2 and 3 (ground of radius 1e6 from 1 above, d = (0, -0.125, -1)):\n");
    std::printf("  f.f       exact %.1Lf  float %.1f\n", ld(f.y) * f.y, double(f.y * f.y));
    std::printf("  r^2       exact %.1Lf  float %.1f\n", ld(ground.radius) * ground.radius,
                double(ground.radius * ground.radius));
    std::printf("  c         exact %.1Lf  float %.1f\n", c_exact, double(c_float));
    std::printf("  with the exact c (rounded to float):  plain %.7f  stable %.7f\n",
                double(plain_near_root(a, half_b, c_rounded)), double(stable_near_root(half_b, c_rounded, disc)));
    std::printf("  with the float c:                     plain %.7f  stable %.7f\n",
                double(plain_near_root(a, half_b, c_float)), double(stable_near_root(half_b, c_float, disc)));
    const vec3<float> down45{0, -1, -1};
    const float h45 = dot(f, down45), disc45 = float(ld(h45) * h45 - ld(dot(down45, down45)) * c_exact);
    std::printf("  45 degrees down, stable pair:  float c %.7f  exact c %.8f\n",
                double(stable_near_root(h45, c_float, disc45)), double(stable_near_root(h45, c_rounded, disc45)));
    std::printf("  exact roots (your intersect_sphere_robust in long double): %.9Lf and, 45 degrees down, %.9Lf\n",
                exact_root(d), exact_root(down45));
}

}  // namespace

int main() {
    try {
        far_sphere();
        huge_ground();
    } catch (const rt::not_implemented& e) {
        std::printf("%s\n", e.what());
        return rt::exit_not_implemented;
    }
    return 0;
}
