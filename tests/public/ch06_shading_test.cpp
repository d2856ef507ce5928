// Public tests for chapter 06: lights, Lambert, Blinn-Phong, shadows, acne.
//
// Each case is one idea from the lecture. When a check fails, its message
// names that idea; the numbers follow. The shadow tests use chapters 02 and
// 04 to intersect their blockers (build with -DRT_STUDENT_CHAPTERS=06 to take
// those from the reference solutions).
#include "04-plane/plane.hpp"
#include "06-shading/shading.hpp"
#include "02-sphere/sphere.hpp"

#include "rpc/served.hpp"
#include "test_support.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

using namespace rt;
using rt::test::close;
using rt::test::describe;

namespace {

std::string describe_color(const color& c) {
    std::ostringstream s;
    s.precision(7);
    s << "(" << c.r << ", " << c.g << ", " << c.b << ")";
    return s.str();
}

// A grey matte material: diffuse 0.5 in every channel, no highlight.
material matte() {
    material m;
    m.diffuse = color(0.5f);
    m.specular = color(0.0f);
    return m;
}

// A light of the given intensity at position p.
point_light light_at(vec3d p, float intensity) {
    return point_light{p, color(intensity)};
}

// An occlusion test over one sphere, with chapter 02's intersection. It is a
// served one (tests/support/rpc/served.hpp): under the grader, the grader's
// own process answers each shadow ray your shade() asks about, and only the
// ones your own shadow_ray() gives for the lights; asking about another ray
// makes shade() throw.
template <class T>
ch06::occlusion_test<T> blocked_by(const sphere<T>& blocker) {
    return rt::test::served_occlusion<T>{[blocker](const ray<T>& r, const interval<T>& range) {
        return ch02::intersect_sphere(blocker, r, range).has_value();
    }};
}

template <class T>
ch06::occlusion_test<T> nothing_blocks() {
    return rt::test::nothing_blocks<T>();
}

// Shoots a grid of camera rays from `eye` at sphere s, and for every hit the
// light can see sends the shadow ray back against the same sphere. Returns how
// many of those shadow rays hit the sphere they leave (shadow acne); `lit`
// receives how many hits were checked.
template <class T>
int self_shadowed_hits(const sphere<T>& s, const vec3<T>& eye, const vec3<T>& light, int& lit) {
    int acne = 0;
    lit = 0;
    const int n = 40;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            // Aim across the sphere's whole disc as seen from the eye.
            const T u = (T(i) + T(0.5)) / T(n) * T(2) - T(1);
            const T v = (T(j) + T(0.5)) / T(n) * T(2) - T(1);
            const vec3<T> aim = s.center + s.radius * vec3<T>(u, v, T(0));
            const ray<T> r{eye, aim - eye};
            auto hit = ch02::intersect_sphere(s, r, interval<T>{T(0), infinity<T>});
            if (!hit || !(ch06::lambert(hit->normal, light - hit->point) > T(0))) continue;
            ++lit;
            const ch06::shadow_query<T> q = ch06::shadow_ray(hit->point, hit->normal, light);
            if (ch02::intersect_sphere(s, q.r, q.range)) ++acne;
        }
    return acne;
}


// --- what a wrong answer points to ------------------------------------------------
// ctest may run these tests in any order (it starts the slow ones first), so
// a shade() test's message must not blame the idea its test was written for
// when the numbers point elsewhere. shade() is built from the smaller
// functions, so these probes ask each of them one easy question and name the
// first classic mistake they find (empty when none): a wrong falloff is then
// not reported for a Lambert term that was never normalised.
template <class T>
std::string building_block_diagnosis() {
    const vec3<T> up(0, 1, 0);
    const T straight_up = ch06::lambert(up, vec3<T>(0, 5, 0));
    if (!close(straight_up, T(1)))
        return " [lambert() gives " + std::to_string(double(straight_up)) +
               " for a light straight above, 5 units away, where the cosine is 1: it must divide dot(n, l) by "
               "|n| |l| (normalise both vectors), or a farther light looks brighter, which undoes the "
               "inverse-square law.]";
    if (ch06::lambert(up, vec3<T>(1, -1, 0)) < T(0))
        return " [lambert() is negative for a light below the surface: clamp the cosine at 0, a light "
               "cannot take energy away.]";
    const ch06::shadow_query<T> q = ch06::shadow_ray(vec3<T>(0), up, vec3<T>(0, 4, 0));
    if (!(q.range.max < infinity<T>))
        return " [shadow_ray() returns an unbounded range: end it at the light's distance, so blockers beyond "
               "the light cast no shadow.]";
    if (!close(length(q.r.direction), T(1)))
        return " [shadow_ray()'s direction is not a unit vector, so t is not a distance and (0, distance to the "
               "light) is not the segment up to the light: normalise the direction.]";
    if (!(q.r.origin.y > T(0)))
        return " [shadow_ray() starts exactly on the surface: offset its origin along the normal, towards the "
               "light (shadow acne).]";
    return "";
}

// The same for shade() itself, after the building blocks: a light of
// intensity 4 straight above a diffuse 0.5 surface, at distances 1 and 2.
template <class T>
std::string shade_diagnosis() {
    const std::string blocks = building_block_diagnosis<T>();
    if (!blocks.empty()) return blocks;
    const vec3<T> p(0, 0, 0), n(0, 1, 0), eye(0, 1, 1);
    material m;
    m.diffuse = color(0.5f);
    m.specular = color(0.0f);
    const auto lit = [&](double height) {
        return ch06::shade(p, n, eye, m, {point_light{{0, height, 0}, color(4.0f)}}, color(0),
                           nothing_blocks<T>())
            .r;
    };
    const float at_1 = lit(1), at_2 = lit(2);
    if (at_1 == 0.0f && at_2 == 0.0f)
        return " [shade() gives no light at all from a light straight above: is the vector to the light "
               "light - point (from the point towards the light)?]";
    if (close(at_2, 1.0f))
        return " [shade() gives 1 at distance 2 for 0.5 * 4 / 2^2 = 0.5: it divides by d, not by d^2 "
               "(inverse-square law).]";
    if (close(at_2, at_1))
        return " [shade() gives the same light at distances 1 and 2: divide the intensity by d^2 "
               "(inverse-square law).]";
    return "";
}

}  // namespace

// --- Lambert's cosine law ------------------------------------------------------

TEST_CASE_TEMPLATE("a light straight above gives full Lambert", T, RT_SCALARS) {
    const T c = ch06::lambert(vec3<T>(0, 1, 0), vec3<T>(0, 5, 0));
    CHECK_MESSAGE(close(c, T(1)),
                  "a light straight above the surface (along the normal) meets it head-on: cos(0) = 1. "
                  "The light is 5 units away but Lambert only depends on the angle. Got "
                      << c
                      << std::string(close(c, T(5)) ? ": that is dot(n, l) without dividing by |n| |l| (not normalised)" : ""));
}

TEST_CASE_TEMPLATE("Lambert follows the cosine of the angle", T, RT_SCALARS) {
    // 60 degrees from the normal: (sin 60, cos 60, 0) = (0.866.., 0.5, 0).
    const T c = ch06::lambert(vec3<T>(0, 1, 0), vec3<T>(std::sqrt(T(3)) / T(2), T(0.5), T(0)));
    CHECK_MESSAGE(close(c, T(0.5)),
                  "light arriving 60 degrees from the normal spreads over twice the area: Lambert gives "
                  "cos(60 deg) = 0.5. Got "
                      << c);
}

TEST_CASE_TEMPLATE("Lambert uses unit vectors", T, RT_SCALARS) {
    // A normal of length 2 and a light 45 degrees up, sqrt(18) away.
    const T c = ch06::lambert(vec3<T>(0, 2, 0), vec3<T>(3, 3, 0));
    CHECK_MESSAGE(close(c, std::sqrt(T(0.5))),
                  "cos(theta) = dot(n, l) / (|n| |l|): the vectors here have lengths 2 and sqrt(18), the "
                  "angle is 45 degrees, so the answer is cos(45 deg) = 0.7071. Got "
                      << c
                      << std::string(close(c, T(6)) ? ": that is dot(n, l) of the vectors as given, not normalised" : ""));
}

TEST_CASE_TEMPLATE("a light below the surface gives zero not negative", T, RT_SCALARS) {
    const vec3<T> up(0, 1, 0);
    const T below = ch06::lambert(up, vec3<T>(1, -1, 0));
    const T straight_below = ch06::lambert(up, vec3<T>(0, -4, 0));
    const T grazing = ch06::lambert(up, vec3<T>(1, 0, 0));
    CHECK_MESSAGE(below == T(0),
                  "a light 45 degrees below the surface cannot light it: cos is negative (-0.707) and must be "
                  "clamped to 0, otherwise the light would take energy away. Got "
                      << below);
    CHECK_MESSAGE(straight_below == T(0), "a light straight below the surface gives 0 (cos = -1 clamped); got "
                                              << straight_below);
    CHECK_MESSAGE(grazing == T(0), "light along the surface (90 degrees) gives cos = 0; got " << grazing);
}

// --- Blinn-Phong -------------------------------------------------------------------

TEST_CASE_TEMPLATE("the highlight peaks in the mirror direction", T, RT_SCALARS) {
    const vec3<T> n(0, 1, 0), to_light(1, 1, 0);
    const T mirror = ch06::blinn_phong(n, to_light, vec3<T>(-2, 2, 0), T(32));
    CHECK_MESSAGE(close(mirror, T(1)),
                  "the viewer sits in the mirror direction of the light (both 45 degrees from the normal, on "
                  "opposite sides): the half vector l + v is the normal itself, so (n . h)^shininess = 1. Got "
                      << mirror
                      << std::string(close(ch06::blinn_phong(n, to_light, vec3<T>(-1, 1, 0), T(32)), T(1))
                              ? ". With a viewer vector as long as the light vector you do get 1: build h from "
                                "the UNIT vectors, l/|l| + v/|v|, or the longer one pulls h towards itself"
                              : ""));
    const T off_mirror = ch06::blinn_phong(n, to_light, vec3<T>(-1, 2, 0), T(32));
    CHECK_MESSAGE((off_mirror > T(0) && off_mirror < mirror),
                  "away from the mirror direction the half vector tilts off the normal and the highlight "
                  "fades: expected a value between 0 and "
                      << mirror << ", got " << off_mirror
                      << std::string(off_mirror >= T(1) ? ". A cosine of 1 (or more, clamped) away from the mirror direction "
                                               "means h was not normalised: l/|l| + v/|v| is up to 2 long, so "
                                               "divide n . h by |n| |h|"
                                             : ""));
    // Viewer next to the light: h = l, 45 degrees from n: cos(45)^32 = 2^-16.
    const T beside_light = ch06::blinn_phong(n, to_light, vec3<T>(1, 1, 0), T(32));
    CHECK_MESSAGE(close(beside_light, std::pow(T(0.5), T(16)), T(0)),  // scale 0: a relative comparison
                  "with the viewer beside the light, h = l is 45 degrees from the normal: "
                  "cos(45 deg)^32 = 2^-16 = 1.53e-5. Use the half vector of the UNIT light and viewer "
                  "directions. Got "
                      << beside_light);
}

TEST_CASE_TEMPLATE("a light below the surface makes no highlight", T, RT_SCALARS) {
    // Viewer and light both below: the half vector even points along -n.
    const T h = ch06::blinn_phong(vec3<T>(0, 1, 0), vec3<T>(1, -1, 0), vec3<T>(-1, -1, 0), T(8));
    CHECK_MESSAGE(h == T(0), "a light below the surface cannot make a highlight on it; got " << h);
}

// --- shade(): lights add up, fall off, and can be blocked -------------------------

TEST_CASE_TEMPLATE("inverse-square falloff", T, RT_SCALARS) {
    const vec3<T> p(0, 0, 0), n(0, 1, 0), eye(0, 1, 1);
    const material m = matte();
    const color at_1 = ch06::shade(p, n, eye, m, {light_at({0, 1, 0}, 4)}, color(0), nothing_blocks<T>());
    const color at_2 = ch06::shade(p, n, eye, m, {light_at({0, 2, 0}, 4)}, color(0), nothing_blocks<T>());
    CHECK_MESSAGE(close(at_1.r, 2.0f),
                  "a light of intensity 4 at distance 1 straight above a diffuse 0.5 surface delivers "
                  "0.5 * 4 / 1^2 = 2. Got "
                      << describe_color(at_1) << shade_diagnosis<T>());
    CHECK_MESSAGE(close(at_2.r, 0.5f),
                  "twice as far, the same light spreads over four times the area: 0.5 * 4 / 2^2 = 0.5 "
                  "(inverse-square law). Got "
                      << describe_color(at_2) << shade_diagnosis<T>());
}

TEST_CASE_TEMPLATE("ambient light is always there", T, RT_SCALARS) {
    const color c = ch06::shade(vec3<T>(0, 0, 0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), matte(),
                                {light_at({0, -3, 0}, 9)}, color(0.1f, 0.2f, 0.4f), nothing_blocks<T>());
    CHECK_MESSAGE((close(c.r, 0.05f) && close(c.g, 0.1f) && close(c.b, 0.2f)),
                  "the only light is below the surface, so only ambient * diffuse = (0.1, 0.2, 0.4) * 0.5 "
                  "remains. Got "
                      << describe_color(c) << shade_diagnosis<T>());
}

TEST_CASE_TEMPLATE("a blocker between the point and the light casts a shadow", T, RT_SCALARS) {
    const sphere<T> blocker{{0, 2, 0}, T(0.5), 0};  // halfway between the point and the light
    const color c = ch06::shade(vec3<T>(0, 0, 0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), matte(),
                                {light_at({0, 4, 0}, 16)}, color(0.2f), blocked_by(blocker));
    CHECK_MESSAGE(close(c.r, 0.1f),
                  "a sphere sits on the segment from the point to the light, so the shadow ray hits it and "
                  "the light does not count: only ambient * diffuse = 0.2 * 0.5 = 0.1 is left. Got "
                      << describe_color(c) << shade_diagnosis<T>());
}

TEST_CASE_TEMPLATE("a blocker beyond the light casts no shadow", T, RT_SCALARS) {
    const sphere<T> beyond{{0, 6, 0}, T(1), 0};  // above the light, on the same line
    const color c = ch06::shade(vec3<T>(0, 0, 0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), matte(),
                                {light_at({0, 4, 0}, 16)}, color(0), blocked_by(beyond));
    CHECK_MESSAGE(close(c.r, 0.5f),
                  "the sphere is on the shadow ray's line but beyond the light (t from 5 to 7, light at "
                  "t = 4): only blockers with t < the light's distance cast a shadow. Expected "
                  "0.5 * 16 / 4^2 = 0.5, got "
                      << describe_color(c) << shade_diagnosis<T>());
}

// --- the shadow ray and shadow acne -----------------------------------------------

TEST_CASE_TEMPLATE("the shadow ray ends at the light", T, RT_SCALARS) {
    const ch06::shadow_query<T> q = ch06::shadow_ray(vec3<T>(1, 0, 0), vec3<T>(0, 1, 0), vec3<T>(1, 3, 4));
    const vec3<T> light(1, 3, 4);
    CHECK_MESSAGE(close(length(q.r.direction), T(1)),
                  "the shadow ray's direction is a unit vector, so t measures distance; its length is "
                      << length(q.r.direction));
    const vec3<T> end = q.r.at(q.range.max);
    CHECK_MESSAGE(close(length(end - light), T(0), T(5)),
                  "tmax is the distance to the light, so r.at(tmax) is the light itself, "
                      << describe(light) << "; got " << describe(end));
    CHECK_MESSAGE(q.range.min == T(0), "the shadow ray starts at t = 0 (its origin is already off the surface)");
}

TEST_CASE_TEMPLATE("the shadow ray starts on the light's side of the surface", T, RT_SCALARS) {
    const vec3<T> p(2, 0, 3), n(0, 1, 0);
    const vec3<T> above = ch06::shadow_ray_origin(p, n, vec3<T>(1, 5, 0));
    const vec3<T> below = ch06::shadow_ray_origin(p, n, vec3<T>(1, -5, 0));
    CHECK_MESSAGE(above.y > T(0),
                  "the light is above the surface, so the origin must move up, along +normal, off the "
                  "surface; got "
                      << describe(above));
    CHECK_MESSAGE(below.y < T(0),
                  "the light is below the surface, so the origin must move to that side, along -normal; got "
                      << describe(below));
    CHECK_MESSAGE((std::fabs(above.y) < T(1e-3) && std::fabs(below.y) < T(1e-3)),
                  "the offset is a rounding-error-sized step, not a jump: far below 1e-3 for a point with "
                  "coordinates around 3. Got "
                      << describe(above) << " and " << describe(below));
}

TEST_CASE_TEMPLATE("no shadow acne on a unit sphere", T, RT_SCALARS) {
    const sphere<T> s{{0, 0, -3}, T(1), 0};
    int lit = 0;
    const int acne = self_shadowed_hits(s, vec3<T>(0, 0, 0), vec3<T>(4, 5, 2), lit);
    REQUIRE(lit > 100);
    CHECK_MESSAGE(acne == 0,
                  "shadow acne: " << acne << " of " << lit
                                  << " lit points sent a shadow ray that hit their own sphere. A computed hit "
                                     "point can lie a rounding error inside the surface; start the shadow ray "
                                     "a little off the surface, along the normal, on the light's side");
}

TEST_CASE_TEMPLATE("no shadow acne on a huge sphere far away", T, RT_SCALARS) {
    // Radius 1e4, 1e5 away: in float one unit in the last place of 1e5 is 0.0078,
    // so a fixed offset like 1e-4 is lost when it is added to the point.
    const sphere<T> s{{0, 0, T(-1e5)}, T(1e4), 0};
    int lit = 0;
    const int acne = self_shadowed_hits(s, vec3<T>(0, 0, 0), vec3<T>(T(1e5), T(1e5), T(-5e4)), lit);
    REQUIRE(lit > 100);
    CHECK_MESSAGE(acne == 0,
                  "shadow acne at large coordinates: "
                      << acne << " of " << lit
                      << " lit points re-hit their own sphere. The hit point's rounding error grows with its "
                         "coordinates (about 1e5 here), so the offset must grow with them too: scale it by "
                         "max(1, |x|, |y|, |z|) rather than using a fixed epsilon");
}

TEST_CASE_TEMPLATE("a tiny scene keeps its shadows", T, RT_SCALARS) {
    // Everything is a millimetre in size: a ball of radius 2e-4 floats 1e-3
    // above a point on the floor, right under the light.
    const sphere<T> ball{{0, T(1e-3), 0}, T(2e-4), 0};
    const vec3<T> p(0, 0, 0), n(0, 1, 0);
    const color c = ch06::shade(p, n, vec3<T>(0, T(1e-3), T(1e-3)), matte(), {light_at({0, 0.01, 0}, 1)}, color(0),
                                blocked_by(ball));
    CHECK_MESSAGE(c.r == 0.0f,
                  "the tiny ball sits between the floor point and the light, so the point is in shadow. If the "
                  "light got through, the shadow ray started beyond the ball: a fixed offset such as 0.01 is "
                  "larger than this whole scene. Got "
                      << describe_color(c) << building_block_diagnosis<T>());
}

TEST_CASE_TEMPLATE("a lit point on a plane does not shadow itself", T, RT_SCALARS) {
    // A plane through a point far from the origin, hit from a camera near it.
    const plane<T> floor{{T(3e4), T(-2e3), T(-5e4)}, {0, 1, 0}, 0};
    const vec3<T> eye(T(3e4), T(-1.99e3), T(-5e4) + T(50));
    const vec3<T> light(T(3e4) + T(500), T(0), T(-5e4));
    int lit = 0, acne = 0;
    for (int i = 0; i < 30; ++i)
        for (int j = 0; j < 30; ++j) {
            const vec3<T> target(T(3e4) + T(i * 7 - 100), T(-2e3), T(-5e4) - T(j * 5));
            auto hit = ch04::intersect_plane(floor, ray<T>{eye, target - eye}, interval<T>{T(0), infinity<T>});
            if (!hit) continue;
            ++lit;
            const ch06::shadow_query<T> q = ch06::shadow_ray(hit->point, hit->normal, light);
            if (ch04::intersect_plane(floor, q.r, q.range)) ++acne;
        }
    REQUIRE(lit > 100);
    CHECK_MESSAGE(acne == 0, "shadow acne on a plane at coordinates around 5e4: "
                                 << acne << " of " << lit
                                 << " lit points re-hit the plane they lie on. Offset the shadow ray's origin "
                                    "along the normal by an amount that grows with the point's coordinates");
}

TEST_CASE_TEMPLATE("a blocked light takes away only its own light", T, RT_SCALARS) {
    // Two lights above the point; a sphere blocks the first one only.
    const sphere<T> blocker{{0, 2, 0}, T(0.5), 0};  // on the way to the light at (0, 4, 0)
    const std::vector<point_light> lights{light_at({0, 4, 0}, 16), light_at({3, 4, 0}, 25)};
    const color c = ch06::shade(vec3<T>(0, 0, 0), vec3<T>(0, 1, 0), vec3<T>(0, 1, 1), matte(), lights, color(0.2f),
                                blocked_by(blocker));
    // The second light: 25 / 5^2 = 1, cos = 4/5, diffuse 0.5 -> 0.4; plus ambient 0.2 * 0.5 = 0.1.
    CHECK_MESSAGE(close(c.r, 0.5f),
                  "the sphere blocks the light at (0,4,0) but not the one at (3,4,0): each light's shadow ray "
                  "decides for that light alone, so the answer is ambient 0.1 plus 0.5 * 25 / 5^2 * cos = 0.4 "
                  "from the second light, 0.5. Got "
                      << describe_color(c)
                      << (!shade_diagnosis<T>().empty() || !close(c.r, 0.1f)
                              ? shade_diagnosis<T>()
                              : std::string(": only ambient, as if one blocked light darkened the point for every "
                                            "light. Skip only the blocked light (continue), do not return")));
}

TEST_CASE_TEMPLATE("the shadow offset does not depend on the normal's length", T, RT_SCALARS) {
    // The same point and light, with normals of lengths 1, 1000 and 0.001.
    const vec3<T> p(1, 2, 3), to_light(0, 5, 1);
    const T unit_step = length(ch06::shadow_ray_origin(p, vec3<T>(0, 1, 0), to_light) - p);
    const T long_step = length(ch06::shadow_ray_origin(p, vec3<T>(0, 1000, 0), to_light) - p);
    const T short_step = length(ch06::shadow_ray_origin(p, vec3<T>(0, T(1e-3), 0), to_light) - p);
    REQUIRE_MESSAGE(unit_step > T(0), "the shadow ray's origin must move off the surface; it did not move");
    CHECK_MESSAGE((long_step < T(2) * unit_step && long_step > T(0.5) * unit_step && short_step < T(2) * unit_step &&
                   short_step > T(0.5) * unit_step),
                  "the normal only gives the direction of the offset, and a normal may have any length: move by "
                  "offset * normal / |normal|. With normals of length 1, 1000 and 0.001 the origin moved by "
                      << unit_step << ", " << long_step << " and " << short_step);
}

TEST_CASE_TEMPLATE("shade lights the side the given normal is on", T, RT_SCALARS) {
    // The ground y = 0 seen from below: the hit reports the plane's outward normal (0, 1, 0), and the
    // one face rule (common/hit_record.hpp) gives the normal on the viewer's side, (0, -1, 0). A light
    // below the ground lights the side the viewer sees.
    const ray<T> up{{0, -1, -1}, {0, 1, 1}};
    hit_record<T> hit;
    hit.t = 1;
    hit.point = vec3<T>(0, 0, 0);
    hit.normal = vec3<T>(0, 1, 0);
    const color c = ch06::shade(hit.point, hit.facing_normal(up), -up.direction, matte(), {light_at({0, -1, 0}, 4)},
                                color(0), nothing_blocks<T>());
    CHECK_MESSAGE(close(c.r, 2.0f),
                  "the normal (0, -1, 0) and the light are below the surface: lit from straight below, "
                  "0.5 * 4 / 1^2 = 2. Got "
                      << describe_color(c) << shade_diagnosis<T>());
    // The caller chose the side; shade() does not choose it again.
    const color far_side = ch06::shade(hit.point, hit.normal, -up.direction, matte(), {light_at({0, -1, 0}, 4)},
                                       color(0), nothing_blocks<T>());
    CHECK_MESSAGE(close(far_side.r, 0.0f),
                  "given the normal (0, 1, 0), shade() lights the side above the ground, and the only light is "
                  "below it: nothing but ambient (0). Use the normal as given; do not turn it towards the viewer "
                  "(the caller passes hit.facing_normal(r), already turned, once). Got "
                      << describe_color(far_side));
}
