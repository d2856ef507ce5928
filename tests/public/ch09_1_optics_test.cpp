// Public tests for chapter 09, exercise 1: reflect, refract, Fresnel and
// Schlick (optics.hpp).
//
// Each case is one idea from the lecture; a failed check names it, then
// shows the numbers. References are computed here in long double from the
// same inputs, by a different route where one exists (Fresnel's sine and
// tangent laws for the reflectance), so a slip in the formula shows.
#include "09-reflection/optics.hpp"

#include "test_support.hpp"

#include <cmath>
#include <random>

using namespace rt;
using rt::ch09::fresnel_dielectric;
using rt::ch09::reflect;
using rt::ch09::refract;
using rt::ch09::schlick;
using rt::test::describe;

namespace {

using ld = long double;

template <class T>
T tol() {
    return sizeof(T) == 4 ? T(2e-5) : T(1e-12);
}

template <class T>
vec3<T> unit(vec3<T> v) {
    return v / length(v);
}

// |a x b| / (|a| |b|): the sine of the angle between a and b.
template <class T>
ld sine_between(const vec3<T>& a, const vec3<T>& b) {
    const vec3<ld> x(a), y(b);
    return std::sqrt(dot(cross(x, y), cross(x, y)) / (dot(x, x) * dot(y, y)));
}

// Fresnel's reflectance from the angles themselves (the sine and tangent
// laws), a different route from the cosine form the header gives.
ld fresnel_by_angles(ld cos_i, ld eta) {
    const ld theta_i = std::acos(cos_i);
    const ld sin_t = eta * std::sin(theta_i);
    if (sin_t >= 1) return 1;
    const ld theta_t = std::asin(sin_t);
    if (theta_i == 0) return ((1 - eta) / (1 + eta)) * ((1 - eta) / (1 + eta));
    const ld rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const ld rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return (rs * rs + rp * rp) / 2;
}

// The directions a test aims at a surface with normal (0, 1, 0): incoming
// at `degrees` from the normal, in the x-y plane.
template <class T>
vec3<T> arriving_at(ld degrees, T length_of_d = 1) {
    const ld a = degrees * 3.14159265358979323846L / 180;
    return T(length_of_d) * vec3<T>(T(std::sin(a)), T(-std::cos(a)), T(0));
}

}  // namespace

TEST_CASE_TEMPLATE("optics: reflect keeps the angle to the normal and stays in the plane of d and n", T, RT_SCALARS) {
    std::mt19937_64 gen(901);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 200; ++i) {
        const vec3<T> n = unit(vec3<T>(T(u(gen)), T(u(gen)), T(u(gen))));
        vec3<T> d(T(u(gen)), T(u(gen)), T(u(gen)));
        if (dot(d, n) > T(0)) d = -d;
        const vec3<T> r = reflect(d, n);
        CAPTURE(describe(d));
        CAPTURE(describe(n));
        CAPTURE(describe(r));
        // The angle: the normal part flips, dot(r, n) = -dot(d, n).
        CHECK_MESSAGE(std::fabs(dot(r, n) + dot(d, n)) <= 8 * tol<T>() * length(d),
                      "the mirror direction leaves at the angle it came in: dot(r, n) = -dot(d, n)");
        // The plane: r - d is along n (only the normal part changed).
        CHECK_MESSAGE(sine_between(r - d, n) <= 1e3L * tol<T>(),
                      "r - d must be parallel to n: reflection changes only d's part along the normal");
    }
}

TEST_CASE_TEMPLATE("optics: reflect keeps the length of d, whatever it is", T, RT_SCALARS) {
    // A ray's direction length is its unit of t (chapter 01): reflect must not normalise.
    const vec3<T> n(0, 1, 0);
    for (T len : {T(1e-3), T(1), T(7), T(1e4)}) {
        const vec3<T> d = arriving_at<T>(30, len);
        const vec3<T> r = reflect(d, n);
        CHECK_MESSAGE(rt::test::close(length(r), length(d)),
                      "|r| must equal |d| = " << length(d) << "; got |r| = " << length(r) << " for r = " << describe(r));
    }
    // Straight down comes straight back up.
    const vec3<T> up = reflect(vec3<T>(0, -2, 0), n);
    CHECK_MESSAGE(up == vec3<T>(0, 2, 0), "a ray straight down onto the floor comes straight back up; got " << describe(up));
}

TEST_CASE_TEMPLATE("optics: refract obeys Snell's law and goes through the surface", T, RT_SCALARS) {
    const vec3<T> n(0, 1, 0);
    for (T eta : {T(1) / T(1.5), T(1) / T(1.33), T(1.5), T(1.2)}) {
        for (ld degrees : {5.0L, 20.0L, 35.0L, 40.0L, 60.0L, 80.0L}) {
            const vec3<T> d = arriving_at<T>(degrees, T(3));
            const ld sin_i = std::sin(degrees * 3.14159265358979323846L / 180);
            CAPTURE(eta);
            CAPTURE(degrees);
            const auto t = refract(d, n, eta);
            if (ld(eta) * sin_i > 1) {
                CHECK_MESSAGE(!t.has_value(), "past the critical angle (eta sin_i > 1) there is no transmitted ray");
                continue;
            }
            REQUIRE_MESSAGE(t.has_value(), "eta sin_i = " << double(ld(eta) * sin_i)
                                                           << " <= 1: the ray is transmitted, refract must give a direction");
            CAPTURE(describe(*t));
            CHECK_MESSAGE(rt::test::is_unit(*t), "the transmitted direction is unit length");
            CHECK_MESSAGE(dot(*t, n) < T(0), "the transmitted ray goes through the surface: dot(t, n) < 0");
            CHECK_MESSAGE(std::fabs(sine_between(*t, -n) - ld(eta) * sin_i) <= 100 * tol<T>(),
                          "Snell: sin(theta_t) = eta sin(theta_i)");
            // Same plane of incidence: the tangential parts point the same way.
            CHECK_MESSAGE(t->x > T(0), "the transmitted ray keeps going the way d went along the surface");
        }
    }
    // Straight through at normal incidence.
    const auto straight = refract(vec3<T>(0, -5, 0), n, T(1) / T(1.5));
    REQUIRE(straight.has_value());
    CHECK_MESSAGE(rt::test::close(*straight, vec3<T>(0, -1, 0)), "at normal incidence the ray goes straight through; got "
                                                                     << describe(*straight));
}

TEST_CASE_TEMPLATE("optics: at the critical angle the ray grazes, just past it there is total internal reflection", T,
                   RT_SCALARS) {
    // From glass (1.5) into air: sin(theta_c) = 1 / 1.5.
    const vec3<T> n(0, 1, 0);
    const T eta = T(1.5);
    const ld critical = std::asin(1 / 1.5L) * 180 / 3.14159265358979323846L;
    // Exactly at it, up to rounding: either no ray, or one along the surface.
    const auto at = refract(arriving_at<T>(critical), n, eta);
    if (at) CHECK_MESSAGE(std::fabs(at->y) <= T(std::sqrt(double(tol<T>())) * 4),
                          "at the critical angle the transmitted ray runs along the surface; got " << describe(*at));
    // A little before: a transmitted ray close to the surface, exactly as Snell says.
    const ld before = critical - 0.01L;
    const auto near = refract(arriving_at<T>(before), n, eta);
    REQUIRE_MESSAGE(near.has_value(), "0.01 degrees before the critical angle the ray is still transmitted");
    const ld sin_t = 1.5L * std::sin(before * 3.14159265358979323846L / 180);
    CHECK_MESSAGE(std::fabs(-ld(near->y) - std::sqrt(1 - sin_t * sin_t)) <= (sizeof(T) == 4 ? 2e-3L : 1e-7L),
                  "cos(theta_t) = sqrt(1 - eta^2 sin^2(theta_i)); got " << describe(*near));
    // Just past it, and at grazing: nothing.
    for (ld degrees : {critical + 0.01L, 60.0L, 89.9L})
        CHECK_MESSAGE(!refract(arriving_at<T>(degrees), n, eta).has_value(),
                      "at " << double(degrees) << " degrees inside glass the light is totally reflected: expected std::nullopt");
    // Entering glass from air there is never total internal reflection.
    CHECK_MESSAGE(refract(arriving_at<T>(89.9L), n, T(1) / T(1.5)).has_value(),
                  "from air into glass (eta < 1) every ray is transmitted, even at 89.9 degrees");
}

TEST_CASE_TEMPLATE("optics: normal incidence reflects ((n1 - n2) / (n1 + n2))^2", T, RT_SCALARS) {
    for (ld n2 : {1.33L, 1.5L, 2.42L}) {
        const ld want = ((1 - n2) / (1 + n2)) * ((1 - n2) / (1 + n2));
        const T entering = fresnel_dielectric(T(1), T(1 / n2));
        const T leaving = fresnel_dielectric(T(1), T(n2));
        CHECK_MESSAGE(std::fabs(ld(entering) - want) <= 10 * tol<T>(),
                      "air into index " << double(n2) << ": R = " << double(want) << ", got " << entering);
        CHECK_MESSAGE(std::fabs(ld(leaving) - want) <= 10 * tol<T>(),
                      "index " << double(n2) << " into air, straight out: the same R = " << double(want) << ", got " << leaving);
    }
    CHECK_MESSAGE(std::fabs(fresnel_dielectric(T(1), T(1) / T(1.5)) - T(0.04)) <= 10 * tol<T>(),
                  "air and glass of index 1.5: 4% is reflected");
}

TEST_CASE_TEMPLATE("optics: fresnel_dielectric follows Fresnel's sine and tangent laws", T, RT_SCALARS) {
    for (ld eta : {1 / 1.5L, 1.5L, 1 / 2.42L}) {
        for (ld degrees = 0.5L; degrees < 90; degrees += 2.5L) {
            const ld cos_i = std::cos(degrees * 3.14159265358979323846L / 180);
            const ld want = fresnel_by_angles(ld(T(cos_i)), ld(T(eta)));
            const T got = fresnel_dielectric(T(cos_i), T(eta));
            CHECK_MESSAGE(std::fabs(ld(got) - want) <= 50 * tol<T>(),
                          "eta " << double(eta) << " at " << double(degrees) << " degrees: R = " << double(want)
                                 << " (the exact formula, not an approximation), got " << got);
        }
    }
}

TEST_CASE_TEMPLATE("optics: all light is reflected at grazing incidence and under total internal reflection", T,
                   RT_SCALARS) {
    CHECK_MESSAGE(fresnel_dielectric(T(0), T(1) / T(1.5)) == doctest::Approx(1.0),
                  "at grazing incidence (cos_i = 0) a surface is a perfect mirror: R = 1");
    CHECK_MESSAGE(fresnel_dielectric(T(0.3), T(1.5)) == T(1), "inside glass past the critical angle R is exactly 1");
    CHECK_MESSAGE(schlick(T(0.3), T(1.5)) == T(1), "schlick: inside glass past the critical angle R is exactly 1");
}

TEST_CASE_TEMPLATE("optics: reflected light plus transmitted light is all of it, seen from either side", T, RT_SCALARS) {
    // The same interface reflects the same share whichever way light
    // crosses it: R(theta_i, eta) = R(theta_t, 1 / eta). So 1 - R, what is
    // transmitted, is the same both ways too.
    for (ld degrees = 1; degrees < 89; degrees += 4) {
        const ld cos_i = std::cos(degrees * 3.14159265358979323846L / 180);
        const ld sin_t = std::sin(degrees * 3.14159265358979323846L / 180) / 1.5L;
        const ld cos_t = std::sqrt(1 - sin_t * sin_t);
        const T from_air = fresnel_dielectric(T(cos_i), T(1) / T(1.5));
        const T from_glass = fresnel_dielectric(T(cos_t), T(1.5));
        CHECK_MESSAGE(std::fabs(from_air - from_glass) <= 50 * tol<T>(),
                      "at " << double(degrees) << " degrees from air: R = " << from_air
                            << ", and from inside the glass along the refracted ray R = " << from_glass);
        CHECK_MESSAGE((from_air >= T(0) && from_air <= T(1)), "R is a fraction, in [0, 1]");
    }
}

TEST_CASE_TEMPLATE("optics: Schlick's approximation is exact at both ends and close in between", T, RT_SCALARS) {
    for (T eta : {T(1) / T(1.5), T(1.5)}) {
        CHECK_MESSAGE(std::fabs(schlick(T(1), eta) - fresnel_dielectric(T(1), eta)) <= 10 * tol<T>(),
                      "Schlick's R0 is Fresnel's at normal incidence (eta " << eta << ")");
        ld worst = 0;
        for (T c = T(0.001); c < T(1); c += T(0.001)) worst = std::max(worst, ld(std::fabs(schlick(c, eta) - fresnel_dielectric(c, eta))));
        // The README measures Schlick's largest error for glass: 0.0357, near 85 degrees from air.
        CHECK_MESSAGE(worst <= 0.04L, "Schlick stays within 0.04 of Fresnel for glass (eta " << eta << "), "
                                           "with the cosine on the air side; worst seen " << double(worst));
        CHECK_MESSAGE(worst > 1e-4L, "schlick must be the approximation, not the exact formula (eta " << eta << ")");
    }
    CHECK_MESSAGE(schlick(T(0), T(1) / T(1.5)) == doctest::Approx(1.0), "Schlick at grazing incidence is 1");
}
